"""Helpers shared by the bs04 sections: the paper's facts
(results/reference/bs04_facts.csv) and what is read from them in more than
one section."""

# the S curve's segment counts bs04 gives (Sec. 2.4, Fig. 7), by eps
_S_COUNTS = (("seg_S_eps1e-2", 1e-2), ("seg_S_eps1e-3", 1e-3), ("seg_S_eps1e-5", 1e-5))


def facts(ctx):
    """The rows of bs04_facts.csv by their id."""
    return {r["id"]: r for r in ctx.ref("bs04_facts.csv")}


def quote(facts, key):
    """'Paper (bs04 <where>): *<statement>*' of fact `key`; "" if it is absent."""
    if key not in facts:
        return ""
    return f"Paper (bs04 {facts[key]['where']}): *{facts[key]['statement']}*"


def s_counts(facts):
    """{eps: segments (float)} of bs04's S curve where the facts give them."""
    return {eps: float(facts[key]["value"]) for key, eps in _S_COUNTS if key in facts}
