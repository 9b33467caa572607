"""Moodle's grading worksheet in the teacher's language (mechanisms.course.moodle): English, Russian and Ukrainian
worksheets, UTF-8 with a byte-order mark as Moodle writes them, round-trip with their own headers; only the grade
and feedback cells change.

The worksheets below are written by hand from Moodle's language strings (mod/assign/gradingtable.php writes the
header with get_string: ``assign/recordid``, ``fullname``, ``email``, ``assign/status``, ``gradenoun``,
``assign/maxgrade``, ``assign/gradecanbechanged``, ``assign/lastmodifiedsubmission``, ``assign/lastmodifiedgrade``,
``assignfeedback_comments/pluginname``; the identifier is ``assign/hiddenuser`` and the participant's number,
without a space in the ru and uk packs), quoted as PHP's fputcsv quotes (a cell with a space). Expected grades by
hand: 10 × right / 15 (5 quantities at 3 positions): 15 right → 10.00, 14 → 9.33, none → 0.00.
"""

from __future__ import annotations

import codecs
import csv
import pathlib

import pytest

from mechanisms.cli import main
from mechanisms.course.moodle import WorksheetError, read_worksheet
from test_moodle import make_course, phi


WORKSHEETS = {
    "en": (
        'Identifier,"Full name","Email address",Status,Grade,"Maximum grade","Grade can be changed",'
        '"Last modified (submission)","Last modified (grade)","Feedback comments"\n'
        '"Participant 2318104","Olena Kovalenko",olena.kovalenko@example.edu,"Submitted for grading",,10.00,Yes,'
        '"Monday, 2 March 2026, 10:15 AM",-,\n'
        '"Participant 2318105","Taras Shevchuk",taras.shevchuk@example.edu,"Submitted for grading",,10.00,Yes,'
        '"Monday, 2 March 2026, 11:40 AM",-,\n'
        '"Participant 2318106","Iryna Bondar",iryna.bondar@example.edu,"No submission",,10.00,Yes,-,-,\n'),
    "ru": (
        'Идентификатор,"Полное имя","Адрес электронной почты",Статус,Оценка,"Максимальная оценка",'
        '"Оценка может быть изменена","Последнее изменение (ответ)","Последнее изменение (оценка)",'
        '"Отзыв в виде комментария"\n'
        'Участник2318104,"Олена Коваленко",olena.kovalenko@example.edu,"Отправлено для оценивания",,10.00,Да,'
        '"понедельник, 2 марта 2026, 10:15",-,\n'
        'Участник2318105,"Тарас Шевчук",taras.shevchuk@example.edu,"Отправлено для оценивания",,10.00,Да,'
        '"понедельник, 2 марта 2026, 11:40",-,\n'
        'Участник2318106,"Ирина Бондарь",iryna.bondar@example.edu,"Ответ не представлен",,10.00,Да,-,-,\n'),
    "uk": (
        'Ідентифікатор,"Повна назва","Електронна пошта",Статус,Оцінка,"Максимальна оцінка",'
        '"Оцінка може бути змінена","Востаннє змінювалося (здача)","Востаннє змінювалося (оцінка)",'
        '"Відгук - коментарем"\n'
        'Учасник2318104,"Олена Коваленко",olena.kovalenko@example.edu,"Здано на оцінення",,10.00,Так,'
        '"понеділок, 2 березня 2026, 10:15",-,\n'
        'Учасник2318105,"Тарас Шевчук",taras.shevchuk@example.edu,"Здано на оцінення",,10.00,Так,'
        '"понеділок, 2 березня 2026, 11:40",-,\n'
        'Учасник2318106,"Ірина Бондар",iryna.bondar@example.edu,"Немає відповіді",,10.00,Так,-,-,\n'),
}

# the three rows' grade and feedback cells as check fills them ({s02_phi1} … are the key's crank angles)
FILLED = {
    "2318104": ("10.00", "15 of 15 answers right (100 %)."),
    "2318105": ("9.33", "14 of 15 answers right (93 %). Wrong: position 1 (φ = {s02_phi1}°): B.v."),
    "2318106": ("0.00", "0 of 15 answers right (0 %). Missing: position 1 (φ = {s03_phi1}°): all; position 2 "
                        "(φ = {s03_phi2}°): all; position 3 (φ = {s03_phi3}°): all."),
}


def expected_text(language: str) -> str:
    """The worksheet with the grade (5th) and feedback (last) cells filled by hand, everything else as it was."""
    lines = WORKSHEETS[language].splitlines(keepends=True)
    out = [lines[0]]
    for line in lines[1:]:
        number = next(n for n in FILLED if n in line)
        grade, feedback = FILLED[number]
        head, _, tail = line.rpartition(",,10.00,")          # the empty grade cell before the maximum grade
        assert tail.endswith(",-,\n")                         # the last modified (grade) and the empty feedback
        out.append(head + f",{grade},10.00," + tail[:-1] + feedback + "\n")
    return "".join(out)


def write(path: pathlib.Path, text: str) -> pathlib.Path:
    path.write_bytes(codecs.BOM_UTF8 + text.encode("utf-8"))    # as Moodle writes it: UTF-8 with a BOM
    return path


def course(folder: pathlib.Path, roster: pathlib.Path) -> tuple[pathlib.Path, pathlib.Path, dict[str, str]]:
    """An assignment from the class list ``roster`` (:func:`test_moodle.make_course`: s01 all right, s02 one wrong,
    s03 no answers): the key, the answers and the key's crank angles."""
    make_course(folder, roster)
    return folder / "course" / "key.csv", folder / "answers.csv", phi(folder)


@pytest.mark.parametrize("language", ["en", "ru", "uk"])
def test_a_worksheet_in_any_language_is_the_class_list_and_round_trips(tmp_path, capsys, language):
    worksheet = write(tmp_path / f"{language}.csv", WORKSHEETS[language])
    key, answers, phi = course(tmp_path, worksheet)
    people = list(csv.DictReader(key.open(encoding="utf8")))
    assert (people[0]["email"], people[3]["email"]) == ("olena.kovalenko@example.edu", "taras.shevchuk@example.edu")
    assert people[0]["identifier"] == {"en": "Participant 2318104", "ru": "Участник2318104",
                                       "uk": "Учасник2318104"}[language]
    out = tmp_path / "graded.csv"
    assert main(["check", str(key), str(answers), "--moodle", str(worksheet), "--moodle-out", str(out)]) == 0
    assert "Moodle worksheet: 3 grades and feedback comments written" in capsys.readouterr().out
    assert out.read_bytes() == codecs.BOM_UTF8 + expected_text(language).format(**phi).encode("utf-8")


@pytest.mark.parametrize("language", ["ru", "uk"])
def test_a_key_from_an_english_worksheet_fills_one_in_another_language(tmp_path, language):
    # the teacher switched the interface language between the two downloads: the participants' numbers match
    key, answers, phi = course(tmp_path, write(tmp_path / "en.csv", WORKSHEETS["en"]))
    worksheet = write(tmp_path / f"{language}.csv", WORKSHEETS[language])
    assert main(["check", str(key), str(answers), "--moodle", str(worksheet), "--moodle-out",
                 str(tmp_path / "out.csv")]) == 0
    assert (tmp_path / "out.csv").read_bytes() == codecs.BOM_UTF8 + expected_text(language).format(**phi).encode()


def test_columns_are_found_by_what_they_hold_whatever_their_names(tmp_path):
    # names in no language the package knows (made up): the identifier, e-mail, maximum grade, grade and the
    # feedback (the last column, empty) are found by their cells
    names = "Ident,Nomo,Retpoŝto,Stato,Noto,Maksimumo,Ŝanĝebla,Lasta (sendo),Lasta (noto),Komentoj"
    text = names + "\n" + WORKSHEETS["en"].split("\n", 1)[1]
    sheet = read_worksheet(write(tmp_path / "eo.csv", text))
    assert sheet.columns == {"identifier": 0, "email": 2, "maximum": 5, "grade": 4, "feedback": 9}


def test_an_id_number_column_is_not_taken_for_the_maximum_grade(tmp_path):
    # showuseridentity adds "ID number" after the name; its numbers differ row by row, the maximum grade does not
    lines = WORKSHEETS["uk"].splitlines(keepends=True)
    text = lines[0].replace('"Повна назва",', '"Повна назва","Індивідуальний номер",') + "".join(
        line.replace('",', f'",{700 + i},', 1) for i, line in enumerate(lines[1:]))
    sheet = read_worksheet(write(tmp_path / "uk-id.csv", text))
    assert (sheet.columns["maximum"], sheet.columns["grade"]) == (6, 5)


def test_a_worksheet_whose_feedback_column_cannot_be_told(tmp_path):
    # every row already has a comment, and the column's name is in no known language: refused, not guessed
    lines = WORKSHEETS["en"].replace('"Feedback comments"', "Komentoj").splitlines(keepends=True)
    text = lines[0] + "".join(line[:-1] + "ok\n" for line in lines[1:])
    with pytest.raises(WorksheetError, match="no column 'Feedback comments'"):
        read_worksheet(write(tmp_path / "x.csv", text))
