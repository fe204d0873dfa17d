"""The package a lab installs: one namespace, a wheel that works outside the checkout,
errors that are also the builtins they mean, and format versions that readers check.

The wheel test builds the wheel from this checkout, installs it with its dependencies in a
fresh virtual environment, and runs the README's main command and ``gaitc firmware build``
from a folder outside the checkout, next to a user's own ``analysis.py``, ``solver.py`` and
``diagnostics.py``.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tomllib
import venv
import zipfile
from pathlib import Path

import pytest
from packages import ROOT, WHEEL_PACKAGES

import gaitc
from gaitc.hw.firmware import missing_tools

#: Modules a research folder often holds; gaitc must not import them in place of its own.
SHADOWS = ("analysis", "solver", "diagnostics", "verifier", "gr1", "gaitsim")


def _shadowing_folder(folder: Path) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    for name in SHADOWS:
        (folder / f"{name}.py").write_text(
            f"raise ImportError('the user\\'s own {name}.py was imported')\n", encoding="utf-8")
    return folder


@pytest.fixture(scope="module")
def wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    # a copy of the sources, so that the build leaves nothing (egg-info, build/) behind
    source = tmp_path_factory.mktemp("source") / "gaitc"
    shutil.copytree(ROOT, source, symlinks=True, ignore=shutil.ignore_patterns(
        ".venv", ".git", "*.egg-info", "build", "__pycache__", ".mypy_cache", ".ruff_cache",
        ".pytest_cache", ".hypothesis"))
    env = {**os.environ, "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    # the environment's own setuptools when it is new enough (fast, offline), else pip's
    # isolated build with the pyproject's build requirements
    for isolation in (["--no-build-isolation"], []):
        done = subprocess.run(
            [sys.executable, "-m", "pip", "wheel", "--no-deps", *isolation, "-q",
             "-w", str(out), str(source)],
            capture_output=True, text=True, check=False, cwd=out, env=env)
        if done.returncode == 0:
            break
    assert done.returncode == 0, done.stderr
    (found,) = out.glob("gaitc-*.whl")
    return found


def test_the_wheel_installs_only_the_three_packages(wheel: Path) -> None:
    """gaitc, its front end and the SLUGS formats; not peers, which only bench/ and tests/
    use (issue 61)."""
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
    tops = {name.split("/")[0] for name in names if not name.split("/")[0].endswith(
        (".dist-info", ".data"))}
    assert tops == set(WHEEL_PACKAGES) == {"gaitc", "ltlcompiler", "slugs_bridge"}
    top_level = next((n for n in names if n.endswith(".dist-info/top_level.txt")), None)
    if top_level is not None:
        with zipfile.ZipFile(wheel) as archive:
            listed = set(archive.read(top_level).decode().split())
        assert listed == set(WHEEL_PACKAGES)
    # the data a user without a checkout needs
    for needed in ("ltlcompiler/gait.lark", "gaitc/hw/board/gaitboard.c",
                   "gaitc/hw/board/harness.c", "gaitc/examples/thesis_robot_a.gait",
                   "gaitc/examples/robots/radial8.yaml", "gaitc/py.typed"):
        assert needed in names, needed


def test_the_api_ignores_a_users_own_modules(tmp_path: Path) -> None:
    folder = _shadowing_folder(tmp_path / "research")
    script = (
        "import gaitc\n"
        f"verdict = gaitc.check({str(ROOT / 'specs' / 'patrol_2x2.gait')!r})\n"
        "print(verdict.realizable)\n"
        "import gaitc.analysis, gaitc.solver, gaitc.diagnostics\n"
    )
    done = subprocess.run([sys.executable, "-c", script], cwd=folder, capture_output=True,
                          text=True, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "True"


def test_importing_a_low_layer_does_not_load_the_facade() -> None:
    """``gaitc/__init__`` is lazy: ltlcompiler and slugs_bridge import gaitc.diagnostics and
    gaitc.ir without pulling in the solver, the simulator or the command line."""
    script = ("import sys, ltlcompiler.parser, slugs_bridge.slugsin\n"
              "print(sorted(m for m in sys.modules if m.startswith(('gaitc.api', 'gaitc.cli',"
              " 'gaitc.solver', 'gaitc.sim'))))\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_errors_are_the_builtins_they_mean(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError) as missing:
        gaitc.load(str(tmp_path / "missing.gait"))
    assert isinstance(missing.value, gaitc.GaitcError)
    assert isinstance(missing.value, OSError) and isinstance(missing.value, gaitc.UsageError)
    assert str(missing.value) == f"cannot read '{tmp_path / 'missing.gait'}': no such file"
    bad = tmp_path / "bad.gait"
    bad.write_text("robot \"x\"\nlegs L1..L2 health 0\n", encoding="utf-8")
    with pytest.raises(ValueError) as value:
        gaitc.load(str(bad))
    assert isinstance(value.value, gaitc.GaitcError) and value.value.span is not None
    with pytest.raises(ValueError):
        gaitc.check(str(ROOT / "specs" / "patrol_2x2.gait"), semantics="nonsense")


def test_version_is_reported(capsys: pytest.CaptureFixture[str]) -> None:
    from importlib.metadata import version

    from gaitc.cli import main

    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0
    assert capsys.readouterr().out.strip() == f"gaitc {gaitc.__version__}"
    assert gaitc.__version__ == version("gaitc")


def test_examples_are_copied_and_never_overwritten(tmp_path: Path) -> None:
    copied = gaitc.copy_examples(tmp_path / "ex")
    assert "thesis_robot_a.gait" in copied.files and "robots/radial8.yaml" in copied.files
    for name in copied.files:
        assert (tmp_path / "ex" / name).read_bytes() == (ROOT / "specs" / name).read_bytes()
    (tmp_path / "ex" / "patrol_2x2.gait").write_text("mine", encoding="utf-8")
    with pytest.raises(OSError) as clash:
        gaitc.copy_examples(tmp_path / "ex")
    assert "exists" in str(clash.value) and "--force" in str(clash.value)
    assert (tmp_path / "ex" / "patrol_2x2.gait").read_text(encoding="utf-8") == "mine"
    gaitc.copy_examples(tmp_path / "ex", overwrite=True)
    assert (tmp_path / "ex" / "patrol_2x2.gait").read_bytes() == (
        ROOT / "specs" / "patrol_2x2.gait").read_bytes()


def _declared() -> tuple[str, ...]:
    """The Python versions gaitc declares: its classifiers (tests/codebase/
    test_python_versions.py checks that they agree with ``requires-python``)."""
    with (ROOT / "pyproject.toml").open("rb") as handle:
        classifiers = tomllib.load(handle)["project"]["classifiers"]
    prefix = "Programming Language :: Python :: 3."
    return tuple(c.removeprefix("Programming Language :: Python :: ") for c in classifiers
                 if c.startswith(prefix))


DECLARED = _declared()


def _interpreter(version: str) -> str | None:
    """A Python of ``version`` on this machine (PATH, then pyenv's versions), or None."""
    if ".".join(map(str, sys.version_info[:2])) == version:
        return sys.executable
    candidates = [shutil.which(f"python{version}")]
    root = Path(os.environ.get("PYENV_ROOT", Path.home() / ".pyenv")) / "versions"
    candidates += sorted(str(p) for p in root.glob(f"{version}.*/bin/python{version}"))
    for found in candidates:
        if found and subprocess.run([found, "--version"], capture_output=True,
                                    check=False).returncode == 0:
            return found
    return None


@pytest.mark.parametrize("version", DECLARED)
def test_the_wheel_works_from_a_fresh_environment(wheel: Path, tmp_path: Path,
                                                  version: str) -> None:
    """On every declared Python this machine has (issue 61: 3.10 was declared, but its
    ``pip install`` failed): a fresh environment, the wheel, the README's first job."""
    python_exe = _interpreter(version)
    if python_exe is None:
        pytest.skip(f"no Python {version} on this machine")
    env_dir = tmp_path / "venv"
    clean = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    if python_exe == sys.executable:
        venv.EnvBuilder(with_pip=True).create(env_dir)
    else:
        made = subprocess.run([python_exe, "-m", "venv", str(env_dir)], capture_output=True,
                              text=True, check=False, env=clean)
        assert made.returncode == 0, made.stderr
    python = env_dir / "bin" / "python"
    install = subprocess.run(
        [str(python), "-m", "pip", "install", "-q", "--disable-pip-version-check", str(wheel)],
        capture_output=True, text=True, check=False, cwd=tmp_path, env=clean)
    if install.returncode != 0 and "No matching distribution" in install.stderr:
        pytest.skip(f"a dependency is not in the package index here: {install.stderr[-300:]}")
    assert install.returncode == 0, install.stderr
    gaitc_bin = env_dir / "bin" / "gaitc"
    work = _shadowing_folder(tmp_path / "lab")

    def run(*argv: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([str(gaitc_bin), *argv], cwd=work, capture_output=True,
                              text=True, check=False, env=clean)

    where = subprocess.run([str(python), "-c", "import gaitc, sys; print(gaitc.__file__); "
                            "print('%d.%d' % sys.version_info[:2])"],
                           cwd=work, capture_output=True, text=True, check=False, env=clean)
    assert str(env_dir) in where.stdout and str(ROOT) not in where.stdout, where
    assert where.stdout.split()[-1] == version
    assert run("--version").stdout.strip() == f"gaitc {gaitc.__version__}"
    assert run("examples", "specs").returncode == 0
    synth = run("synth", "specs/thesis_robot_a.gait", "-o", "robot_a.controller.json", "--json")
    assert synth.returncode == 0, synth.stderr
    assert json.loads(synth.stdout)["verdict"] == "realizable"
    assert (work / "robot_a.controller.json").exists()
    if python_exe == sys.executable and not missing_tools():
        firmware = run("firmware", "build", "-o", "fw")
        assert firmware.returncode == 0, firmware.stderr
        assert (work / "fw" / "gaitboard.hex").exists()


def test_files_from_a_newer_gaitc_are_refused_with_a_clear_message(tmp_path: Path) -> None:
    """Each format gaitc reads back checks its version: a controller or a run written by a
    newer gaitc is named as such, with the file, line and the way out."""
    spec = gaitc.load(ROOT / "specs" / "patrol_2x2.gait")
    found = gaitc.synthesize(spec)
    found.save(tmp_path / "c.json")
    data = json.loads((tmp_path / "c.json").read_text(encoding="utf-8"))
    assert data["gaitc"]["format"] == 1
    data["gaitc"]["format"] = 7
    (tmp_path / "c.json").write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(gaitc.ControllerError) as newer:
        gaitc.verify(spec, tmp_path / "c.json")
    assert newer.value.message == ("this controller file is format version 7, written by a "
                                   "newer gaitc; this gaitc reads versions up to 1")
    assert newer.value.hint is not None and "upgrade gaitc" in newer.value.hint
    run = gaitc.simulate(spec, found, steps=2)
    from gaitc.sim.run import read_jsonl, save_run

    save_run(run, tmp_path / "r.jsonl")
    lines = (tmp_path / "r.jsonl").read_text(encoding="utf-8").splitlines()
    head = json.loads(lines[0])
    assert head["kind"] == "run" and head["format"] == 2
    assert len(read_jsonl(tmp_path / "r.jsonl").steps) == len(run.steps)
    head["format"] = 3
    (tmp_path / "r.jsonl").write_text("\n".join([json.dumps(head), *lines[1:]]) + "\n",
                                      encoding="utf-8")
    with pytest.raises(gaitc.ScenarioError) as run_newer:
        read_jsonl(tmp_path / "r.jsonl")
    assert run_newer.value.message.startswith("this run file is format version 3, written by "
                                              "a newer gaitc")
    assert run_newer.value.span is not None and run_newer.value.span.line == 1


def test_every_public_name_has_a_home() -> None:
    """``gaitc.__all__`` and the lazy table agree, and every name loads."""
    assert sorted(gaitc.__all__) == sorted(gaitc._HOMES)
    for name in gaitc.__all__:
        assert getattr(gaitc, name) is not None, name
