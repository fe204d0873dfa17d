"""The ROS 2 tests: skipped without the ``ros`` extra (saying how to install it)."""

from __future__ import annotations

import pytest
from ros_graph import MISSING


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    for item in items:
        if "tests/ros/" in str(item.path).replace("\\", "/"):
            item.add_marker(pytest.mark.ros)
            if MISSING is not None and "no_extra" not in item.name:
                item.add_marker(pytest.mark.skip(reason=MISSING))
