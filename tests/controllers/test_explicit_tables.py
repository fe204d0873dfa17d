"""The explicit controller's tables layout (issue 51): written, read back, proved, refused.

A controller saved in the tables layout (a name ending in ``.gz``) must read back equal to
the one saved, node for node, and be accepted by the verifier; SLUGS's JSON stays the
layout of other names and of ``layout="slugs-json"``.  A file cut short, damaged, followed
by other bytes, edited by hand or from a newer gaitc is refused with a message that names
the file and says what is wrong (pinned word for word where the words are the point).
"""

from __future__ import annotations

import gzip
import hashlib
import json
from pathlib import Path
from typing import Any

import pytest
from packages import ROOT

import gaitc
from gaitc.diagnostics import ControllerError, UsageError
from gaitc.forms.explicit import GZIP_HEADER, Layout, layout_for, tables_bytes
from gaitc.forms.reader import read_controller, read_document
from gaitc.forms.synthesis import Synthesis
from gaitc.ir.controller import Controller

ROBOT_A = ROOT / "specs" / "thesis_robot_a.gait"
ROBOT_A_HEALTH2 = ROOT / "specs" / "thesis_robot_a_health2.gait"


@pytest.fixture(scope="module")
def robot_a() -> Synthesis:
    found = gaitc.synthesize(gaitc.load(ROBOT_A), form="explicit", verify=False)
    assert isinstance(found.controller, Controller)
    return found


def _write(tmp_path: Path, name: str, data: bytes) -> Path:
    path = tmp_path / name
    path.write_bytes(data)
    return path


def _unpacked(path: Path) -> dict[str, Any]:
    data: dict[str, Any] = json.loads(gzip.decompress(path.read_bytes()))
    return data


def _packed(tmp_path: Path, document: dict[str, Any], digest: bool = True) -> Path:
    """``document`` written as a tables file, its digest made to match when ``digest``."""
    body = {k: v for k, v in document.items() if k != "digest"}
    if digest:
        canonical = json.dumps(body, sort_keys=True, separators=(",", ":")).encode()
        document = {**body, "digest": "sha256:" + hashlib.sha256(canonical).hexdigest()}
    return _write(tmp_path, "edited.ctl", gzip.compress(json.dumps(document).encode()))


def _refusal(path: Path) -> str:
    with pytest.raises(ControllerError) as caught:
        read_controller(path, gaitc.load(ROBOT_A))
    assert caught.value.span is not None and caught.value.span.file == str(path)
    return caught.value.message


def test_layout_follows_the_name() -> None:
    assert layout_for("robot.ctl.gz") == Layout.TABLES
    assert layout_for("robot.controller.GZ") == Layout.TABLES
    assert layout_for("robot.json") == Layout.SLUGS_JSON
    assert layout_for("robot.ctl") == Layout.SLUGS_JSON
    assert layout_for("-") == Layout.SLUGS_JSON


def test_tables_read_back_equal_and_are_proved(robot_a: Synthesis, tmp_path: Path) -> None:
    path = tmp_path / "robot_a.ctl.gz"
    robot_a.save(path)
    data = path.read_bytes()
    assert data.startswith(GZIP_HEADER)
    back = read_controller(path, gaitc.load(ROBOT_A))
    assert back == robot_a.controller
    report = gaitc.verify(gaitc.load(ROBOT_A), path)
    assert report.ok, report.problems
    robot_a.save(tmp_path / "again.ctl.gz")
    assert (tmp_path / "again.ctl.gz").read_bytes() == data  # deterministic


def test_tables_share_each_state_once(robot_a: Synthesis, tmp_path: Path) -> None:
    path = tmp_path / "robot_a.ctl.gz"
    robot_a.save(path)
    document = _unpacked(path)
    assert robot_a.controller is not None and isinstance(robot_a.controller, Controller)
    nodes = robot_a.controller.nodes
    assert len(document["states"]) == len({n.state for n in nodes})
    assert len(document["nodes"]["state"]) == len(nodes)
    assert document["variables"] == list(robot_a.controller.variables)
    assert "values" not in document["gaitc"]  # derived from the bits on reading


def test_slugs_json_stays_for_other_names(robot_a: Synthesis, tmp_path: Path) -> None:
    slugs = tmp_path / "robot_a.json"
    robot_a.save(slugs)
    data = json.loads(slugs.read_text(encoding="utf-8"))
    assert set(data["nodes"]["0"]) == {"rank", "state", "trans"}
    assert read_controller(slugs, gaitc.load(ROBOT_A)) == robot_a.controller
    assert robot_a.controller is not None
    plain = tmp_path / "robot_a.ctl"
    robot_a.save(plain)
    assert plain.read_text(encoding="utf-8") == slugs.read_text(encoding="utf-8")
    forced = tmp_path / "interchange.gz"
    robot_a.save(forced, layout="slugs-json")
    assert forced.read_text(encoding="utf-8") == slugs.read_text(encoding="utf-8")
    packed = tmp_path / "packed.json"
    robot_a.save(packed, layout="tables")
    assert packed.read_bytes().startswith(GZIP_HEADER)
    # the tables are much smaller than SLUGS's JSON of the same controller
    assert 10 * packed.stat().st_size < slugs.stat().st_size


def test_a_counterstrategy_reads_back(tmp_path: Path) -> None:
    spec = gaitc.load(ROBOT_A_HEALTH2)
    found = gaitc.counterstrategy(spec, verify=False)
    path = tmp_path / "counter.ctl.gz"
    found.save(path)
    assert read_controller(path, spec) == found.controller
    assert gaitc.verify(spec, path).ok


def test_other_forms_have_one_layout(tmp_path: Path) -> None:
    found = gaitc.synthesize(gaitc.load(ROOT / "specs" / "patrol_2x2.gait"), form="symbolic",
                             verify=False)
    with pytest.raises(UsageError, match="one file layout, JSON"):
        found.save(tmp_path / "s.ctl", layout="tables")
    found.save(tmp_path / "s.ctl")
    assert json.loads((tmp_path / "s.ctl").read_text(encoding="utf-8"))["gaitc"]


def test_a_file_cut_short_is_refused(robot_a: Synthesis, tmp_path: Path) -> None:
    data = tmp_path / "x.ctl.gz"
    robot_a.save(data)
    raw = data.read_bytes()
    path = _write(tmp_path, "cut.ctl", raw[: len(raw) // 2])
    assert _refusal(path) == (f"the file ends after {len(raw) // 2} bytes, inside its "
                              "compressed data: it was cut short (a copy or a write that did "
                              "not finish)")


def test_a_changed_byte_is_refused(robot_a: Synthesis, tmp_path: Path) -> None:
    robot_a.save(tmp_path / "x.ctl.gz")
    raw = bytearray((tmp_path / "x.ctl.gz").read_bytes())
    raw[len(raw) // 2] ^= 0x01
    message = _refusal(_write(tmp_path, "flipped.ctl", bytes(raw)))
    assert message.startswith(("the unpacked data does not match the checksum",
                               "the compressed data is damaged in bytes"))


def test_bytes_after_the_stream_are_refused(robot_a: Synthesis, tmp_path: Path) -> None:
    robot_a.save(tmp_path / "x.ctl.gz")
    raw = (tmp_path / "x.ctl.gz").read_bytes()
    path = _write(tmp_path, "tail.ctl", raw + b"junk")
    assert _refusal(path) == (f"4 bytes follow the end of the compressed data at byte "
                              f"{len(raw)}; a tables file is one gzip stream")


def test_a_hand_edit_breaks_the_digest(robot_a: Synthesis, tmp_path: Path) -> None:
    robot_a.save(tmp_path / "x.ctl.gz")
    document = _unpacked(tmp_path / "x.ctl.gz")
    document["nodes"]["trans"][3] = [0]
    message = _refusal(_packed(tmp_path, document, digest=False))
    assert message.startswith("the digest does not match the contents")


@pytest.mark.parametrize(("edit", "message"), [
    (lambda d: d["nodes"]["trans"].__setitem__(3, [100000]),
     "node 3: its successors must be node indices 0..{last}"),
    (lambda d: d["nodes"]["state"].__setitem__(5, -1),
     "node 5: its state index must be one of 0..{states}, not -1"),
    (lambda d: d["states"].__setitem__(2, "01x"),
     "state 2 must be a string of {width} characters 0 or 1, one per variable"),
    (lambda d: d["nodes"]["rank"].pop(),
     "'nodes.rank' must have one entry per node ({count}, as 'nodes.state')"),
    (lambda d: d.__setitem__("initial", [-2]),
     "'initial' must list node indices 0..{last}"),
    (lambda d: d["gaitc"].__setitem__("kind", "plan"),
     "'gaitc.kind' must be one of strategy, counterstrategy"),
])
def test_a_consistent_but_wrong_file_names_the_place(
        robot_a: Synthesis, tmp_path: Path, edit: Any, message: str) -> None:
    robot_a.save(tmp_path / "x.ctl.gz")
    document = _unpacked(tmp_path / "x.ctl.gz")
    count, width = len(document["nodes"]["state"]), len(document["variables"])
    states = len(document["states"]) - 1
    edit(document)
    assert _refusal(_packed(tmp_path, document)) == message.format(
        last=count - 1, count=count, width=width, states=states)


def test_a_newer_version_says_so(robot_a: Synthesis, tmp_path: Path) -> None:
    robot_a.save(tmp_path / "x.ctl.gz")
    document = _unpacked(tmp_path / "x.ctl.gz")
    document["gaitc"]["version"] = 2
    assert "written by a newer gaitc" in _refusal(_packed(tmp_path, document))


def test_gzip_of_other_text_is_refused(tmp_path: Path) -> None:
    path = _write(tmp_path, "odd.ctl", gzip.compress(b'{"gaitc": {"format": "explicit-t'))
    assert _refusal(path).startswith("the unpacked text is not valid JSON at line 1, column")
    assert read_document(_write(tmp_path, "plain.ctl", gzip.compress(b"[1]"))) == [1]


def test_tables_of_a_small_controller_are_exact() -> None:
    from gaitc.ir.controller import ControllerNode

    ctrl = Controller(variables=("a", "b"), inputs=("a",), outputs=("b",),
                      nodes=(ControllerNode(0, (0, 1), (1,)),
                             ControllerNode(1, (1, 0), (0, 2)),
                             ControllerNode(0, (0, 1), (1,))),
                      initial=(0,))
    document = json.loads(gzip.decompress(tables_bytes(ctrl)))
    assert document["states"] == ["01", "10"]
    assert document["nodes"] == {"state": [0, 1, 0], "rank": [0, 1, 0],
                                 "trans": [[1], [0, 2], [1]]}
    assert document["initial"] == [0]


def test_a_failed_write_leaves_the_old_file(robot_a: Synthesis, tmp_path: Path,
                                            monkeypatch: pytest.MonkeyPatch) -> None:
    """The file is written to a temporary one and renamed: a write that fails halfway
    leaves the old controller whole, and no temporary file behind."""
    import os

    from gaitc.diagnostics import FileAccessError

    path = tmp_path / "robot_a.ctl.gz"
    robot_a.save(path)
    before = path.read_bytes()

    def broken(fd: int) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "fsync", broken)
    with pytest.raises(FileAccessError):
        robot_a.save(path, layout="slugs-json")
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["robot_a.ctl.gz"]
