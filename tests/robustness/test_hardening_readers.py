"""The robot-side YAML readers on the hardened path (issue 38): the map of ``drive --map``
and the sensing file of ``drive --sensing`` report every problem at its file:line:col in the
project's words, deep nesting included, and the span-tracking reader is linear in the size
of its input."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from gaitc.diagnostics import GaitcError, LineTable, Span, source_lines, span_at
from gaitc.diagnostics.yamltext import compose
from gaitc.hw.backend import HardwareError
from gaitc.hw.localisation import RegionMap
from gaitc.hw.sensing import CalibrationError, read_sensing

REGIONS = ("a", "b")


def _map(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "m.yaml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize(("text", "message", "line", "column"), [
    ("regions:\n  a: [[0, 0], [1, 0], {x: 1}]\n", "region a: a polygon point must be [x, y], "
     "two finite numbers", 2, 23),
    ("regions:\n  a: [[0, 0], [1, .nan], [0, 1]]\n", "region a: a polygon point must be "
     "[x, y], two finite numbers", 2, 15),
    ("regions:\n  a: [[0, 0], [1, 0]]\n", "region a: a polygon needs at least 3 [x, y] "
     "points", 2, 6),
    ("regions:\n  c: [[0, 0], [1, 0], [0, 1]]\n", "the map names region 'c', which the spec "
     "has not", 2, 3),
    ("regions: [1, 2]\n", "a map file maps 'regions' to polygons", 1, 10),
    ("just: text\n", "a map file maps 'regions' to polygons", 1, 1),
    ("regions:\n  a: [[0, 0], [1, true], [0, 1]]\n", "region a: a polygon point must be "
     "[x, y], two finite numbers", 2, 15),
])
def test_map_errors_are_positioned(tmp_path: Path, text: str, message: str, line: int,
                                   column: int) -> None:
    path = _map(tmp_path, text)
    with pytest.raises(HardwareError) as caught:
        RegionMap.from_file(path, REGIONS)
    assert caught.value.message == message
    assert caught.value.span == Span(str(path), line, column)


def test_a_map_nested_a_thousand_deep_is_a_positioned_error(tmp_path: Path) -> None:
    path = _map(tmp_path, "regions:\n  a: " + "[" * 1000 + "]" * 1000 + "\n")
    with pytest.raises(HardwareError) as caught:
        RegionMap.from_file(path, REGIONS)
    assert caught.value.message == "the map nests too deeply (the limit is 200 levels)"
    assert caught.value.span is not None and caught.value.span.file == str(path)


def test_a_good_map_reads(tmp_path: Path) -> None:
    path = _map(tmp_path, "regions:\n  a: [[0, 0], [1, 0], [0, 1]]\n"
                "  b: [[1, 0], [2, 0], [2, 1], [1, 1]]\n")
    regions = RegionMap.from_file(path, REGIONS)
    assert regions.region_at(0.2, 0.2) == "a" and regions.region_at(1.5, 0.5) == "b"


@pytest.mark.parametrize(("text", "line", "column"), [
    ("legs:\n  L1: {thresholds: [0.4, .nan]}\n", 2, 26),
    ("legs:\n  L1: {thresholds: [0.2, 0.4]}\n", 2, 20),
    ("legs:\n  L1: {thresholds: [0.4, 0.2], hysteresis: -1}\n", 2, 44),
    ("legs:\n  L1: {thresholds: [0.4, \"0.2\"]}\n", 2, 26),
    ("legs:\n  L1: 3\n", 2, 7),
    ("legs:\n  L1: {thresholds: []}\n", 2, 3),
])
def test_sensing_errors_are_positioned(tmp_path: Path, text: str, line: int,
                                       column: int) -> None:
    path = tmp_path / "s.sensing.yaml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(CalibrationError) as caught:
        read_sensing(path)
    assert caught.value.message == ("leg L1: thresholds must be a descending list of finite "
                                    "numbers and hysteresis a finite number >= 0")
    assert caught.value.span == Span(str(path), line, column)


def test_a_sensing_file_nested_deep_is_a_positioned_error(tmp_path: Path) -> None:
    path = tmp_path / "s.sensing.yaml"
    path.write_text("legs:\n  L1: " + "{a: " * 1000 + "1" + "}" * 1000 + "\n", encoding="utf-8")
    with pytest.raises(CalibrationError) as caught:
        read_sensing(path)
    assert caught.value.message == "the sensing file nests too deeply (the limit is 200 levels)"


def test_a_good_sensing_file_reads(tmp_path: Path) -> None:
    path = tmp_path / "s.sensing.yaml"
    path.write_text("legs:\n  L1: {thresholds: [0.4, 0.2], hysteresis: 0.01}\n  L2: "
                    "{thresholds: [0.5]}\n", encoding="utf-8")
    found = read_sensing(path)
    assert found["L1"].thresholds == (0.4, 0.2) and found["L1"].hysteresis == 0.01
    assert found["L2"].thresholds == (0.5,)


# -- positions in linear time -----------------------------------------------------------------

def _brute(text: str, file: str, offset: int) -> Span:
    """span_at as it was, a count from the start for every offset (quadratic over a file)."""
    offset = max(0, min(offset, len(text)))
    if offset == len(text) and text.endswith("\n"):
        offset -= 2 if text.endswith("\r\n") else 1
    before = text[:offset]
    start = before.rfind("\n") + 1
    column = offset - start + 1
    if column > 1 and text[start:offset].endswith("\r") and text[offset:offset + 1] in ("\n", ""):
        column -= 1
    return Span(file, before.count("\n") + 1, column)


@given(st.text(alphabet="ab\n\r\x85 ", max_size=40), st.data())
def test_the_line_table_gives_the_spans_of_the_count(text: str, data: st.DataObject) -> None:
    table = LineTable(text, "f")
    for offset in data.draw(st.lists(st.integers(-2, len(text) + 2), max_size=8)):
        assert table.span(offset) == _brute(text, "f", offset) == span_at(text, "f", offset)
        if text and 0 <= offset < len(text) and text[offset] != "\n":
            span = table.span(offset)
            assert span.line <= max(1, len(source_lines(text)))


def test_the_yaml_reader_is_linear_in_its_input() -> None:
    def seconds(n: int) -> float:
        text = "items:\n" + "".join(f"  - {{name: n{i}, v: [{i}, {i + 1}]}}\n" for i in range(n))
        began = time.perf_counter()
        compose(text, "f.yaml", GaitcError, "file")
        return time.perf_counter() - began

    small, large = seconds(2000), seconds(16000)
    # eight times the input: a linear reader takes about eight times as long, the old
    # quadratic count about sixty times; the bound leaves room for a loaded machine
    assert large < 20 * small + 0.5


def test_a_sensing_file_for_other_legs_is_refused_where_it_names_them(tmp_path: Path) -> None:
    from gaitc.hw.sensing import HealthSensing

    path = tmp_path / "s.sensing.yaml"
    path.write_text("legs:\n  L1: {thresholds: [0.4]}\n  L9: {thresholds: [0.4]}\n",
                    encoding="utf-8")
    with pytest.raises(CalibrationError) as caught:
        HealthSensing({"L1": 2, "L2": 2}, read_sensing(path))
    assert caught.value.message == ("the sensing file calibrates leg L9, which the spec has "
                                    "not (its legs: L1, L2)")
    assert caught.value.span == Span(str(path), 3, 3)
    path.write_text("legs:\n  L2: {thresholds: [0.4, 0.2]}\n", encoding="utf-8")
    with pytest.raises(CalibrationError) as caught:
        HealthSensing({"L1": 2, "L2": 2}, read_sensing(path))
    assert caught.value.message == "leg L2 is calibrated for 3 levels but the spec gives it 2"
    assert caught.value.span == Span(str(path), 2, 3)


def test_a_calibration_level_beyond_the_languages_limit_is_refused_at_its_line(
        tmp_path: Path) -> None:
    """A level of a billion used to make calibrate list every level below it (a hang the
    fuzz campaign found)."""
    from gaitc.hw.sensing import read_cycles

    path = tmp_path / "legs.csv"
    path.write_text("leg,cycle,level,intensity\nL1,0,1000000000,900\n", encoding="utf-8")
    with pytest.raises(CalibrationError) as caught:
        read_cycles(path)
    assert caught.value.message == ("line 2: levels run from 1 to 100 (the health levels a "
                                    ".gait leg may have) and intensities are finite numbers")
    assert caught.value.span == Span(str(path), 2, 1)


def test_a_bad_byte_after_a_byte_order_mark_is_counted_as_the_readers_count(
        tmp_path: Path) -> None:
    """Line 1's columns start after a byte order mark, in every reader and the printer."""
    path = tmp_path / "m.yaml"
    path.write_bytes(b"\xef\xbb\xbfregion\xbf: 1\n")
    with pytest.raises(HardwareError) as caught:
        RegionMap.from_file(path, REGIONS)
    assert caught.value.span == Span(str(path), 1, 7)


@pytest.mark.parametrize(("rows", "message", "line"), [
    ("0,0.008\n0.05,0.009\n0.10,0.010\n0.05,0.011\n0.20,0.012\n",
     "the times must increase from row to row, but row 4 (0.05 s after the first) is not "
     "later than the row before", 5),
    ("0,0.008\n0,0.009\n0.10,0.010\n0.15,0.011\n", "but row 2 (0 s after the first)", 3),
])
def test_a_step_response_whose_times_go_back_is_refused_at_the_row(
        tmp_path: Path, rows: str, message: str, line: int) -> None:
    """Fuzz campaign of issue 38 (100,000 inputs): a time column that went back made the
    curvature fit start outside its bounds (scipy's ValueError, exit 70)."""
    from gaitc.models.characterization import CharacterizationError, fit_curvature

    path = tmp_path / "step.csv"
    path.write_text("time,curvature\n" + rows, encoding="utf-8")
    with pytest.raises(CharacterizationError) as caught:
        fit_curvature(path)
    assert message in caught.value.message
    assert caught.value.span == Span(str(path), line, 1)


def test_a_step_response_of_a_huge_time_span_fits(tmp_path: Path) -> None:
    """The frequency's first guess, 4 / duration, stays inside its bound however long the
    recording (a last time of 1e19 s gave 4e-19 rad/s, below the bound of 1e-6)."""
    from gaitc.models.characterization import fit_curvature

    path = tmp_path / "step.csv"
    path.write_text("time,curvature\n0,0.008\n0.05,0.009\n0.1,0.01\n0.15,0.011\n1e19,0.02\n",
                    encoding="utf-8")
    fit = fit_curvature(path)
    assert fit.frequency > 0 and abs(fit.curvature - 0.02) < 1e-3


def test_the_fuzz_oracle_reads_an_uncut_line_that_starts_with_dots() -> None:
    """The campaign's one "wrong line" was the oracle's: a CSV line that itself starts
    with "......" is shown uncut at its head, which the oracle took for a cut."""
    from fuzz_oracle import _excerpt_of

    from gaitc.diagnostics import _excerpt

    line = "......time," + "curvature, " * 200
    shown, _, _ = _excerpt(line, 1, 1)
    assert shown.startswith("......time") and _excerpt_of(shown, line, 1)


def test_a_recorded_value_too_large_to_fit_is_refused_at_its_row(tmp_path: Path) -> None:
    """Second campaign of issue 38: a curvature of 1e162 overflowed the fit's squares
    (scipy's "array must not contain infs or NaNs", exit 70)."""
    from gaitc.models.characterization import CharacterizationError, fit_curvature

    path = tmp_path / "step.csv"
    path.write_text("time,curvature\n0,0.008\n0.05,0.009\n0.1,0.01\n0.15," + "1" * 163
                    + "\n0.2,0.012\n", encoding="utf-8")
    with pytest.raises(CharacterizationError) as caught:
        fit_curvature(path)
    assert caught.value.message == (
        f"{path}: row 4 gives a curvature of 1.11e+162 1/mm; recorded values are at most "
        "1e+06 1/mm in size")
    assert caught.value.span == Span(str(path), 5, 1)


def test_a_stiffness_recording_too_large_to_fit_is_refused_at_its_row(tmp_path: Path) -> None:
    from gaitc.models.characterization import CharacterizationError, fit_stiffness

    path = tmp_path / "stiffness.csv"
    path.write_text("state,dx,dy,dz,fx,fy,fz\n1000,1,0,0,1,0,0\n1000,0,1,0,0,1,0\n"
                    "1000,0,0,1e300,0,0,1\n1000,1,1,0,1,1,0\n", encoding="utf-8")
    with pytest.raises(CharacterizationError) as caught:
        fit_stiffness(path)
    assert "row 3 gives a deflection of 1e+300 mm" in caught.value.message
    assert caught.value.span == Span(str(path), 4, 1)
