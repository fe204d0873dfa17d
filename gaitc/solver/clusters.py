"""ρs as clusters with early quantification, for ``Options.partitioned``.

The parts of the system's transition relation are merged, in the order of their supports,
into clusters of at most ``Options.cluster_limit`` nodes; each cluster is paired with the
primed outputs that no later cluster mentions, which CPre may quantify right after it (early
quantification in the style of Burch, Clarke and Long, "Symbolic model checking with
partitioned transition relations", VLSI 1991).  Measured slower than the monolithic ρs on
every bench family (docs/design-notes.md), so no configuration the engine chooses uses it.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from dd.cudd import BDD
    from dd.cudd import Function as BDDNode


def clusters(bdd: BDD, parts: Sequence[BDDNode], post_outputs: set[str],
             limit: int) -> list[tuple[BDDNode, set[str]]]:
    """``parts`` merged into clusters of at most ``limit`` nodes (a part larger than that is
    a cluster alone), each with the primed outputs it may quantify."""
    merged_list: list[BDDNode] = []
    current = bdd.true
    for part in sorted(parts, key=lambda p: sorted(bdd.support(p))):
        merged = current & part
        if current != bdd.true and merged.dag_size > limit:
            merged_list.append(current)
            current = part
        else:
            current = merged
    merged_list.append(current)
    supports = [bdd.support(c) & post_outputs for c in merged_list]
    out: list[tuple[BDDNode, set[str]]] = []
    for k, cluster in enumerate(merged_list):
        later: set[str] = set().union(*supports[k + 1:]) if k + 1 < len(supports) else set()
        out.append((cluster, supports[k] - later))
    return out
