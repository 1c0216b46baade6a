"""Compare car-path implementations on random pairs: length vs OMPL, endpoint reached, time per call.

    PYTHONPATH=. python3 tools/rs_compare.py [--pairs 1000] [--seed 0]

Needs ``pip install ompl`` (the reference) and optionally ``rsplan``.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from lazyground.planning import curves as C


def _timed(fn, pairs):
    t0 = time.perf_counter()
    out = [fn(a, b) for a, b in pairs]
    return out, (time.perf_counter() - t0) / len(pairs) * 1e6


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    from ompl import base as ob

    rng = np.random.default_rng(args.seed)
    lo, hi = [-10, -10, -math.pi], [10, 10, math.pi]
    pairs = list(zip(rng.uniform(lo, hi, (args.pairs, 3)), rng.uniform(lo, hi, (args.pairs, 3))))
    for name, space_cls, ours in (("reeds-shepp", ob.ReedsSheppStateSpace, C.reeds_shepp_word), ("dubins", ob.DubinsStateSpace, C.dubins_word)):
        space = space_cls(1.0)

        def state(q, space=space):
            s = space.allocState()
            s.setX(q[0]), s.setY(q[1]), s.setYaw(q[2])
            return s

        ref, t_ref = _timed(lambda a, b: space.distance(state(a), state(b)), pairs)
        words, t_ours = _timed(lambda a, b: ours(*C.relative(a, b, 1.0)), pairs)
        err = max(abs(C.word_length(w) - d) / d for w, d in zip(words, ref))
        print(f"{name}: ours max relative length error {err:.1e} vs OMPL; {t_ours:.1f} us/call (OMPL binding {t_ref:.1f} us/call)")
        if name == "reeds-shepp":
            try:
                import rsplan.planner as rp
            except ImportError:
                continue
            out, t_rs = _timed(lambda a, b: rp.path(tuple(a), tuple(b), 1.0, 0.0, 10.0), pairs)
            errs = [abs(o.total_length - d) / d for o, d in zip(out, ref)]
            print(f"{name}: rsplan max relative error {max(errs):.1e}, {sum(e > 1e-6 for e in errs)} pairs off by > 1e-6; {t_rs:.1f} us/call")


if __name__ == "__main__":
    main()
