"""The API reference documents every module of the package, once (book/appendix/api-*.md)."""

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "mechanisms"


def test_every_module_has_its_page_once():
    documented = []
    for page in sorted((ROOT / "book" / "appendix").glob("api-*.md")):
        documented += re.findall(r"^\.\. automodule:: (\S+)", page.read_text(encoding="utf8"), flags=re.M)
    modules = sorted("mechanisms." + ".".join(p.relative_to(PACKAGE).with_suffix("").parts)
                     for p in PACKAGE.rglob("*.py")
                     if p.stem != "__init__" and not p.stem.startswith("_") and p.parent != PACKAGE)
    modules.append("mechanisms.cli")
    missing = sorted(set(modules) - set(documented))
    twice = sorted({m for m in documented if documented.count(m) > 1})
    assert not missing and not twice, f"modules without an API page: {missing}; documented twice: {twice}"
