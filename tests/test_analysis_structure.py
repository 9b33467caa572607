"""Tests of mechanisms.analysis.structure: the structural formula, counted by hand."""

import pytest

from mechanisms.analysis.structure import BOOK_STRUCTURES, mobility
from mechanisms.core.errors import InvalidParameterError


def test_mobility_by_hand():
    assert mobility(3, 4) == 1        # four-bar: 3·3 − 2·4
    assert mobility(4, 5) == 2        # five-bar linkage: two inputs needed
    assert mobility(2, 3) == 0        # a triangle of links: a structure
    assert mobility(4, 5, 1) == 1     # one higher pair (a cam contact) removes one more


def test_every_mechanism_of_the_book_has_one_degree_of_freedom():
    assert [s.mobility for s in BOOK_STRUCTURES] == [1] * len(BOOK_STRUCTURES)


@pytest.mark.parametrize("args", [(-1, 0), (3, 2.5), (True, 1)])
def test_bad_counts(args):
    with pytest.raises(InvalidParameterError):
        mobility(*args)


def test_report_names_the_criterion_as_the_book_does():
    # the book (chapters 2, 3 and 6) writes "Kutzbach–Grübler"; the Watt six-bar is n = 5, p₁ = 7
    # (chapter 6, counted by hand: 15 − 14 = 1)
    from mechanisms import load_linkage
    from mechanisms.analysis.structure import structure_of

    text = structure_of(load_linkage("watt-six-bar")).text()
    assert "(Kutzbach–Grübler): W = 3n − 2p₁ − p₂ = 3·5 − 2·7 − 0 = 1" in text
    assert "Chebyshev–Grübler" not in text
