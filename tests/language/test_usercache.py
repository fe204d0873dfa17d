"""The user's cache (gaitc/diagnostics/usercache.py) and the grammar kept in it (issue 48):
plain data that cannot run code, read and written only in a folder that is the user's
alone, never through a link; a planted, foreign or corrupt file is ignored and rebuilt."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from gaitc.diagnostics import GaitcError, usercache
from ltlcompiler import parser

ROOT = Path(__file__).resolve().parents[2]
SPEC = "gaitc/examples/patrol_2x2.gait"
OLD_CACHE = "gait-grammar.lark-cache"  # the name of Lark's pickle cache, before issue 48


class _Plant:
    """Unpickling this creates ``marker``: a stand-in for any code a pickle may run."""

    def __init__(self, marker: Path) -> None:
        self.marker = marker

    def __reduce__(self) -> tuple[object, tuple[str, str]]:
        return (open, (str(self.marker), "w"))


def _lint(home: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "XDG_CACHE_HOME": str(home)}
    return subprocess.run([sys.executable, "-m", "gaitc", "lint", SPEC], capture_output=True,
                          text=True, env=env, cwd=ROOT, check=False)


def _folder(home: Path, mode: int = 0o700) -> Path:
    folder = home / "gaitc"
    folder.mkdir()
    folder.chmod(mode)
    return folder


@pytest.fixture()
def home(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A cache home for this process: ``usercache`` and ``parser._lark`` read it anew."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    yield tmp_path


def _grammar_key() -> str:
    from importlib import resources

    text = resources.files("ltlcompiler").joinpath("gait.lark").read_text(encoding="utf-8")
    return parser._grammar_key(text)


# ---------------------------------------------------------------- planted files
def test_a_planted_pickle_in_a_shared_cache_folder_runs_nothing(tmp_path: Path) -> None:
    folder = _folder(tmp_path, 0o777)
    marker = tmp_path / "ran"
    planted = b"0" * 64 + b"\n" + pickle.dumps(_Plant(marker))  # Lark's cache: hash, pickle
    for name in (OLD_CACHE, parser.GRAMMAR_CACHE):
        (folder / name).write_bytes(planted)
    done = _lint(tmp_path)
    assert (done.returncode, done.stderr) == (0, "")
    assert not marker.exists()
    # a folder others may write is not used at all: nothing read, nothing written
    assert sorted(p.name for p in folder.iterdir()) == sorted([OLD_CACHE, parser.GRAMMAR_CACHE])
    assert (folder / parser.GRAMMAR_CACHE).read_bytes() == planted


def test_a_pickle_in_the_users_own_folder_is_not_unpickled_but_replaced(
        tmp_path: Path) -> None:
    folder = _folder(tmp_path)
    marker = tmp_path / "ran"
    planted = folder / parser.GRAMMAR_CACHE
    planted.write_bytes(b"0" * 64 + b"\n" + pickle.dumps(_Plant(marker)))
    planted.chmod(0o600)
    done = _lint(tmp_path)
    assert (done.returncode, done.stderr) == (0, "")
    assert not marker.exists()
    assert planted.read_bytes().startswith(usercache.FORMAT.encode())


def test_a_planted_link_is_replaced_and_its_target_never_written(tmp_path: Path) -> None:
    folder = _folder(tmp_path)
    victim = tmp_path / "precious.txt"
    victim.write_text("precious\n", encoding="utf-8")
    (folder / parser.GRAMMAR_CACHE).symlink_to(victim)
    done = _lint(tmp_path)
    assert (done.returncode, done.stderr) == (0, "")
    assert victim.read_text(encoding="utf-8") == "precious\n"
    cached = folder / parser.GRAMMAR_CACHE
    assert not cached.is_symlink() and cached.is_file()
    assert cached.read_bytes().startswith(usercache.FORMAT.encode())


def test_a_cache_folder_that_is_a_link_is_not_used(tmp_path: Path) -> None:
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir(mode=0o700)
    (tmp_path / "home").mkdir()
    (tmp_path / "home" / "gaitc").symlink_to(elsewhere)
    done = _lint(tmp_path / "home")
    assert (done.returncode, done.stderr) == (0, "")
    assert list(elsewhere.iterdir()) == []


def test_a_fifo_in_place_of_the_cache_neither_hangs_nor_is_written(home: Path) -> None:
    folder = _folder(home)
    os.mkfifo(folder / "data.json", 0o600)
    assert usercache.load("data.json", "k") is None  # opened without blocking, refused


# ---------------------------------------------------------------- who owns what
def test_the_stored_file_and_a_new_folder_are_the_users_alone(home: Path) -> None:
    usercache.store("data.json", "k", [1, 2])
    folder = home / "gaitc"
    assert folder.stat().st_mode & 0o777 == 0o700
    assert (folder / "data.json").stat().st_mode & 0o777 == 0o600
    assert usercache.load("data.json", "k") == [1, 2]


@pytest.mark.parametrize("mode", [0o770, 0o750, 0o705, 0o701, 0o777, 0o1777])
def test_a_folder_others_may_use_is_neither_read_nor_written(home: Path, mode: int) -> None:
    usercache.store("data.json", "k", [1, 2])
    (home / "gaitc").chmod(mode)
    assert usercache.load("data.json", "k") is None
    usercache.store("data.json", "k", [3])
    (home / "gaitc").chmod(0o700)
    assert usercache.load("data.json", "k") == [1, 2]  # unchanged


@pytest.mark.parametrize("mode", [0o620, 0o602, 0o666])
def test_a_file_others_may_write_is_ignored(home: Path, mode: int) -> None:
    usercache.store("data.json", "k", [1, 2])
    (home / "gaitc" / "data.json").chmod(mode)
    assert usercache.load("data.json", "k") is None
    usercache.store("data.json", "k", [1, 2])  # rebuilt: a new file of the user's alone
    assert (home / "gaitc" / "data.json").stat().st_mode & 0o777 == 0o600
    assert usercache.load("data.json", "k") == [1, 2]


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0,
                    reason="giving a file to another user needs root")
def test_a_file_or_folder_of_another_user_is_ignored(home: Path) -> None:
    usercache.store("data.json", "k", [1, 2])
    os.chown(home / "gaitc" / "data.json", 54321, -1)
    assert usercache.load("data.json", "k") is None
    os.chown(home / "gaitc" / "data.json", os.getuid(), -1)
    assert usercache.load("data.json", "k") == [1, 2]
    os.chown(home / "gaitc", 54321, -1)
    assert usercache.load("data.json", "k") is None


# ---------------------------------------------------------------- corrupt or other data
def test_a_changed_byte_or_another_key_reads_as_missing(home: Path) -> None:
    usercache.store("data.json", "k", {"a": [1, 2, 3]})
    path = home / "gaitc" / "data.json"
    assert usercache.load("data.json", "other") is None
    raw = path.read_bytes()
    path.write_bytes(raw.replace(b"3", b"4"))
    assert usercache.load("data.json", "k") is None
    for broken in (b"", b"no header", raw[:-5], raw.split(b"\n")[0] + b"\n\x80\x81"):
        path.write_bytes(broken)
        assert usercache.load("data.json", "k") is None


def test_a_corrupt_grammar_cache_is_rebuilt(home: Path) -> None:
    reference = parser._lark.__wrapped__()
    path = home / "gaitc" / parser.GRAMMAR_CACHE
    key = _grammar_key()
    spec = (ROOT / SPEC).read_text(encoding="utf-8")
    # right key and digest, but not Lark's data; then bytes that are not JSON at all
    wrong: list[dict[str, object]] = [{"data": {}, "memo": {}},
                                      {"data": {"parser": 1}, "memo": {"x": []}}]
    for data in wrong:
        usercache.store(parser.GRAMMAR_CACHE, key, data)
        rebuilt = parser._lark.__wrapped__()
        assert rebuilt.parse(spec) == reference.parse(spec)
        stored = usercache.load(parser.GRAMMAR_CACHE, key)
        assert stored != data and isinstance(stored, dict)  # written anew
        again = parser._from_cache(stored)
        assert again is not None and again.parse(spec) == reference.parse(spec)
    path.write_bytes(b"not a cache\n" + b"\x80" * 50)
    rebuilt = parser._lark.__wrapped__()
    assert rebuilt.parse(spec) == reference.parse(spec)
    assert path.read_bytes().startswith(usercache.FORMAT.encode())


def test_an_edited_grammar_cache_with_its_digest_computed_again_is_rebuilt(home: Path) -> None:
    """Issue 60: the cache's digest was a plain SHA-256 of its data, so a cache edited to
    swap ``assume`` and ``guarantee`` and given a digest computed again turned an
    unrealizable spec realizable. The seal is keyed by the folder's secret now: the edited
    cache reads as missing and the spec keeps its verdict."""
    import hashlib

    # the corridor whose spill the robot cannot make go away: unrealizable as a guarantee,
    # realizable when read as an assumption
    corridor = (ROOT / "specs" / "corridor_hazard.gait").read_text(encoding="utf-8")
    kept = [line for line in corridor.splitlines()
            if not line.startswith(("guarantee always (next(spill)", "assume always"))]
    spec = home / "spill.gait"
    spec.write_text("\n".join([*kept, "guarantee always eventually !spill", ""]),
                    encoding="utf-8")
    assert _lint(home).returncode == 0  # builds and stores the cache
    path = home / "gaitc" / parser.GRAMMAR_CACHE
    header, _, payload = path.read_bytes().partition(b"\n")
    # the lexer's patterns of the two keywords swapped
    swapped = payload.replace(b'"value":"assume"', b'"value":"@"') \
        .replace(b'"value":"guarantee"', b'"value":"assume"') \
        .replace(b'"value":"@"', b'"value":"guarantee"')
    assert swapped.count(b'"value":"assume"') == 1 and swapped != payload
    fmt_version, key, _seal = header.decode().rsplit(" ", 2)
    # what an editor who knows the format computes: the plain digest, and the keyed one
    # without the secret
    for seal in (hashlib.sha256(swapped).hexdigest(),
                 hashlib.sha256(key.encode() + b"\0" + swapped).hexdigest()):
        path.write_bytes(f"{fmt_version} {key} {seal}".encode() + b"\n" + swapped)
        env = {**os.environ, "XDG_CACHE_HOME": str(home)}
        run = subprocess.run([sys.executable, "-m", "gaitc", "check", str(spec)],
                             capture_output=True, text=True, env=env, cwd=ROOT, check=False)
        assert "unrealizable" in run.stdout, run.stdout + run.stderr
        stored = path.read_bytes().partition(b"\n")[2]
        assert stored != swapped and usercache.load(parser.GRAMMAR_CACHE, key) is not None
    # the edit matters: sealed with the folder's secret, it would be read and flip the verdict
    secret = (home / "gaitc" / usercache.SECRET).read_bytes()
    path.write_bytes(usercache._header(key, swapped, secret) + b"\n" + swapped)
    env = {**os.environ, "XDG_CACHE_HOME": str(home)}
    run = subprocess.run([sys.executable, "-m", "gaitc", "check", str(spec)],
                         capture_output=True, text=True, env=env, cwd=ROOT, check=False)
    assert ": realizable" in run.stdout, run.stdout + run.stderr


def test_a_cache_of_another_gaitc_version_is_another_key(
        monkeypatch: pytest.MonkeyPatch) -> None:
    before = _grammar_key()
    monkeypatch.setattr(parser, "PACKAGE", "0.0.0-other")
    assert _grammar_key() != before


# ---------------------------------------------------------------- round trips
def test_plain_data_round_trips_with_its_tuples_and_keys(home: Path) -> None:
    data = {"a": (1, (2, "x")), "b": {0: [True, None], 7: (), (1, 2): 1.5},
            "\0tuple": [1], "big": 18446744073709551616}
    usercache.store("data.json", "k", data)
    assert usercache.load("data.json", "k") == data


@pytest.mark.parametrize("data", [{"f": print}, {1.5, 2.5}, float("nan"), b"bytes"])
def test_what_json_cannot_give_back_is_not_stored(home: Path, data: object) -> None:
    usercache.store("data.json", "k", data)
    assert not (home / "gaitc" / "data.json").exists()


def _outcome(text: str, name: str) -> str:
    try:
        return repr(parser.parse(text, name))
    except GaitcError as err:
        return f"{type(err).__name__}: {err}"


def test_the_cached_grammar_parses_every_spec_and_error_as_the_built_one(
        home: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    built = parser._lark.__wrapped__()  # builds, stores
    assert (home / "gaitc" / parser.GRAMMAR_CACHE).is_file()
    cached = usercache.load(parser.GRAMMAR_CACHE, _grammar_key())
    assert cached is not None
    loaded = parser._from_cache(cached)
    assert loaded is not None
    sources = sorted((ROOT / "gaitc" / "examples").glob("*.gait"))
    sources += sorted((ROOT / "tests" / "errors").glob("*.gait"))
    texts = [(p.name, p.read_text(encoding="utf-8")) for p in sources]
    texts += [("mine", "robot \"r\"\nlegs L1..L2 health 2\nassume always eventually (")]
    texts += [("word", "guarantee always (eventually x)\n"), ("char", "robot $\n")]
    monkeypatch.setattr(parser, "_lark", lambda: built)
    expected = [_outcome(text, name) for name, text in texts]
    monkeypatch.setattr(parser, "_lark", lambda: loaded)
    assert [_outcome(text, name) for name, text in texts] == expected
    assert sum(o.startswith("SpecFile(") for o in expected) >= 10  # both kinds were met
    assert sum(not o.startswith("SpecFile(") for o in expected) >= 10
