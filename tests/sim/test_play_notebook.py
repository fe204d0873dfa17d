"""The notebook player (issue 39): the widget is built and stepped in a real IPython kernel.

A kernel of this interpreter is started with jupyter_client; the cell builds
``gaitc.player_widget`` for robot A, shows it (the notebook receives a widget view), clicks
move buttons, undo and the strongest pilot, and prints what the model and the SVG map say.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("ipywidgets")
pytest.importorskip("ipykernel")
manager = pytest.importorskip("jupyter_client.manager")

ROOT = Path(__file__).resolve().parents[2]

CELL = """
import json, gaitc
w = gaitc.player_widget("specs/thesis_robot_a.gait")
display(w)
w.buttons[0].click()                 # start at full health
switch = next(b for b in w.buttons if "switch blue on" in b.description)
switch.click()
after_switch = w.player.state.hazard
w.undo_button.click()
w.count.value = 20
w.strongest_button.click()
print(json.dumps({"step": w.player.step, "hazard_after_switch": after_switch,
                  "svg": w.map.value.startswith("<svg"), "robot_drawn": "<circle" in w.map.value,
                  "moves": len(w.buttons), "status": w.status.value}))
"""


def _execute(client: Any, code: str) -> tuple[list[str], list[dict[str, Any]]]:
    printed: list[str] = []
    shown: list[dict[str, Any]] = []

    def hook(message: dict[str, Any]) -> None:
        kind = message["header"]["msg_type"]
        if kind == "stream":
            printed.append(message["content"]["text"])
        elif kind in ("display_data", "execute_result"):
            shown.append(message["content"]["data"])
        elif kind == "error":
            printed.append("\n".join(message["content"]["traceback"]))

    reply = client.execute_interactive(code, timeout=240, output_hook=hook)
    assert reply["content"]["status"] == "ok", "".join(printed)
    return printed, shown


def test_the_widget_steps_in_a_real_kernel() -> None:
    kernel, client = manager.start_new_kernel(kernel_name="python3", cwd=str(ROOT),
                                              startup_timeout=120)
    try:
        printed, shown = _execute(client, CELL)
    finally:
        client.stop_channels()
        kernel.shutdown_kernel(now=True)
    result = json.loads("".join(printed).strip().splitlines()[-1])
    assert result["hazard_after_switch"] == "blue"
    assert result["step"] == 20  # the start, then 20 steps of the pilot after the undo
    assert result["svg"] and result["robot_drawn"] and result["moves"] >= 1
    assert "step 20" in result["status"]
    assert any("application/vnd.jupyter.widget-view+json" in data for data in shown)
