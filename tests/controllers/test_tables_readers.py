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


def _bomb(path: Path, unpacked: int) -> int:
    """A tables-layout file whose text is ``unpacked`` spaces (deflate packs them about a
    thousand to one); the file's size."""
    import zlib

    from gaitc.forms.explicit import GZIP_HEADER

    pack = zlib.compressobj(9, zlib.DEFLATED, -zlib.MAX_WBITS)
    chunk = b" " * (1 << 20)
    with path.open("wb") as out:
        out.write(GZIP_HEADER)
        for _ in range(unpacked >> 20):
            out.write(pack.compress(chunk))
        out.write(pack.flush())
        # the trailer a gzip stream ends with: CRC-32 and length (not checked: reading
        # stops before it)
        out.write(b"\0" * 8)
    return path.stat().st_size


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs /proc")
def test_a_file_that_unpacks_far_past_its_size_is_refused_while_unpacking(
        tmp_path: Path) -> None:
    """Issue 60: a 300 KB file that unpacks to 300 MB was unpacked whole before it was
    refused. Reading stops at 64 times the file's size, so the process stays small."""
    import subprocess
    import sys

    from gaitc.forms.explicit import MAX_RATIO

    bomb = tmp_path / "bomb.ctl.gz"
    size = _bomb(bomb, 300 << 20)
    assert size < 400_000
    # the child reports its own peak memory after the command: VmHWM, its image's high
    # water mark (getrusage's ru_maxrss would count the forking worker's peak too)
    probe = ("import sys\nfrom pathlib import Path\nfrom gaitc.cli import main\n"
             "code = main(sys.argv[1:])\n"
             "hwm = [l for l in Path('/proc/self/status').read_text().splitlines()"
             " if l.startswith('VmHWM:')][0].split()[1]\n"
             "print('peak', hwm, file=sys.stderr)\nsys.exit(code)")
    run = subprocess.run([sys.executable, "-c", probe, "verify", str(ROBOT_A), str(bomb)],
                         capture_output=True, text=True, check=False, timeout=120)
    assert run.returncode == 1, run.stderr
    assert f"bomb.ctl.gz:1:1: error: it unpacks to more than {MAX_RATIO * size} bytes " \
        f"({MAX_RATIO} times its {size} bytes" in run.stderr
    assert "Traceback" not in run.stderr
    peak_kb = int(run.stderr.split("peak ")[-1])
    assert peak_kb < 250_000  # gaitc itself takes about 60 MB: the 300 MB were never held


def test_the_tables_gaitc_writes_stay_far_below_the_ratio(binary: tuple[Path, Path]) -> None:
    import gzip

    from gaitc.forms.explicit import MAX_RATIO

    tables, _ = binary
    packed = tables.read_bytes()
    assert len(gzip.decompress(packed)) < MAX_RATIO / 4 * len(packed)
