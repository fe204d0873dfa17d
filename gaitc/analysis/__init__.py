"""analysis: the answers a user needs beyond the verdict.

Why a spec is unrealizable and what would fix it (:mod:`gaitc.analysis.explanation`: the kind of
failure, a minimal unrealizable core in source terms, the environment's freedoms it needs,
a winning play of the environment, verified repairs, and sanity checks of realizable
specs). Every answer is computed by re-solving variants of the spec with :mod:`gaitc.solver`.
"""
