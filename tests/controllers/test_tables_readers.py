"""The two header readers of gaitc/api/solving.py read the tables layout too (issue 51).

``recorded_encoding`` (which spares ``--encoding`` on verify, simulate, play and drive)
and ``controller_form`` (``render policy``'s test for a compact file) once read only JSON
text: a tables file of a binary-encoded spec failed ``gaitc verify`` without
``--encoding`` and ``render policy`` refused it as not UTF-8.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import gaitc
from gaitc.api.solving import controller_form, recorded_encoding
from gaitc.cli import main
from gaitc.core.modes import Form
from gaitc.forms.explicit import GZIP_MAGIC
from gaitc.forms.synthesis import Synthesis

ROBOT_A = Path(gaitc.__file__).resolve().parent / "examples" / "thesis_robot_a.gait"


@pytest.fixture(scope="module")
def binary(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """Robot A compiled with the binary encoding, in the tables layout and in SLUGS's JSON."""
    folder = tmp_path_factory.mktemp("binary")
    found: Synthesis = gaitc.synthesize(gaitc.load(ROBOT_A, encoding="binary"),
                                        form="explicit", verify=False)
    tables, slugs = folder / "robot_a.ctl.gz", folder / "robot_a.json"
    found.save(tables)
    found.save(slugs)
    assert tables.read_bytes().startswith(GZIP_MAGIC)
    assert not slugs.read_bytes().startswith(GZIP_MAGIC)
    return tables, slugs


def test_the_headers_of_a_tables_file_are_read(binary: tuple[Path, Path]) -> None:
    for path in binary:
        assert recorded_encoding(path) == "binary"
        assert controller_form(path) == Form.EXPLICIT


def test_an_unreadable_file_records_no_encoding(tmp_path: Path) -> None:
    cut = tmp_path / "cut.ctl.gz"
    cut.write_bytes(GZIP_MAGIC + b"\x08")
    assert recorded_encoding(cut) is None
    assert recorded_encoding(tmp_path / "missing.ctl.gz") is None


def test_verify_takes_the_encoding_of_a_tables_file(
        binary: tuple[Path, Path], capsys: pytest.CaptureFixture[str]) -> None:
    tables, _ = binary
    assert main(["verify", str(ROBOT_A), str(tables)]) == 0
    assert capsys.readouterr().out.startswith("verified: strategy ok: ")


def test_render_policy_reads_a_tables_file(
        binary: tuple[Path, Path], capsys: pytest.CaptureFixture[str]) -> None:
    tables, slugs = binary
    assert main(["render", "policy", str(ROBOT_A), str(slugs)]) == 0
    expected = capsys.readouterr().out
    assert main(["render", "policy", str(ROBOT_A), str(tables)]) == 0
    drawn = capsys.readouterr()
    assert drawn.out == expected
    assert "south_c → r14" in drawn.out
    assert "not UTF-8" not in drawn.err
