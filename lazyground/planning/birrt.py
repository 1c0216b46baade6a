"""A bidirectional variant of Algorithm 1 (beyond the paper).

RRT-Connect (Kuffner and LaValle 2000) with a goal *forest*: every goal sample
drawn is the root of its own goal subtree. The two sides take turns:

* **start turn** — the start tree takes one step towards a uniform sample; the
  goal forest then steps greedily towards the new node from its nearest nodes
  (whichever goal samples their subtrees grow from);
* **goal turn** — with probability ``goal_bias`` the goal-selection strategy
  picks a goal sample (the top of the reward-penalty max-heap, or round-robin,
  or at random) and *that* sample's subtree takes one step towards a uniform
  sample: a free step is a reward, a blocked one a penalty, and a weight
  falling below the threshold draws more goal samples, which become new roots
  (paper Sec. III-B/C). Otherwise the forest grows from its node nearest the
  uniform sample, as in RRT-Connect, and nobody is credited. Either way the
  start tree then steps greedily towards the new goal node.

The trees meet when a greedy connection reaches the other tree's new node (it
starts from each of the tree's few nearest nodes in turn); the path is the start
branch, the goal branch back to its root sample, and that sample's approach
segment. The start tree's edges are checked lazily (its new
node and the edge's midpoint when it grows, the whole edge when a path uses it);
the goal trees' edges in full as they grow (see :func:`_step`).
"""

from __future__ import annotations

import numpy as np

from lazyground.planning.problem import PlanResult, PlanStatus
from lazyground.planning.search import Search, path_is_valid
from lazyground.planning.tree import Tree

# Where along a start-tree edge a step checks a configuration besides its end (the rest waits for _join).
LAZY_PROBES = (0.5,)
# A greedy connection starts from the tree's nearest node, then from its next nearest ones, until one
# reaches the new node (``connect_from`` of them, a planner setting): most connections stop at their first
# step (the straight line from the nearest node is blocked), and another nearby node often sees the new one.
# Trying them from distinct goal trees first was no better.


def grow_bidirectional(s: Search, start: np.ndarray) -> PlanResult | None:
    space, rng = s.space, s.rng
    ts = Tree(space)
    ts.add_root(start)
    tg = Tree(space, per_label=True)
    s.trees = [ts, tg]
    s.track_blocked()
    rooted = 0
    start_turn = True
    closest: dict[int, float] = {}  # goal sample -> the smallest gap its subtree has left to the start tree
    connects_selected = bool(getattr(s.selector, "connects_selected", False))
    step = s.settings.step_size
    while s.time_left():
        if not s.have_samples():
            if s.goals.exhausted():
                return s.no_goal()
            continue
        for gi in range(rooted, len(s.samples)):  # new goal samples become roots
            root = tg.add_root(s.samples[gi].q, label=gi)
            if s.straight_step is not None and _shut_in(s, s.samples[gi].q):
                tg.mute(root)
            if s.blocked is not None:
                s.blocked.add()
        rooted = len(s.samples)
        s.iterations += 1
        q_rand = space.sample(rng)
        reached = False
        if start_turn:
            _, a = _extend(s, ts, q_rand, step)
            if a >= 0:
                b, reached = _connect(s, tg, ts.nodes[a])
                if not reached and connects_selected:
                    b, reached = _connect_selected(s, tg, ts.nodes[a], closest, b)
        else:
            # goal turn: the strategy's goal tree grows (with probability goal_bias; credited), else the forest
            gi = s.select() if rng.random() < s.settings.goal_bias else None
            near, b = _extend(s, tg, q_rand, step, gi)
            if b >= 0:
                a, reached = _connect(s, ts, tg.nodes[b])
            if gi is not None:
                if b < 0 and near >= 0:
                    s.failed_from.append((1, near))
                _credit(s, gi, closest, -1.0 if b < 0 else s.space.distance(ts.nodes[a], tg.nodes[b]))
        if reached:  # the connection reached the other tree's new node: a is b
            found = _join(s, ts, a, tg, b)
            if found is not None:
                return found
        start_turn = not start_turn
    return None


def _shut_in(s: Search, q: np.ndarray) -> bool:
    """Whether a car cannot drive a step straight forwards nor backwards from goal sample q (a spot
    with a barrier or posts across its mouth; issue #33); False in a space without ``straight_step``.

    Such a root is left out of the forest's nearest-neighbour queries (it still grows when the strategy
    selects it, and its subtree's later nodes are queried as any): with hundreds of blocked spots the
    forest's nearest node to a sample or to a new start-tree node was mostly such a root, whose steps
    all fail. At most two edge checks per goal sample (mostly one pose each). Fixed lot, cover-connect,
    seeds 0-5, 2,000-iteration cap: median iterations 183 -> 138 at N = 64, 440 (5 of 6 solved) -> 362
    (6 of 6) at N = 256; no reachable spot's sample was muted."""
    if s.straight_step is None:
        return False
    step = s.settings.step_size
    for sign in (1.0, -1.0):
        ahead = np.array([q[0] + sign * np.cos(q[2]), q[1] + sign * np.sin(q[2]), q[2]])
        q_new = s.straight_step(q, ahead, step)
        # (its end first: one check rules out most blocked steps, a barrier or kerb across the car's end pose)
        if q_new is not None and s.checker.config_free(q_new) and s.motion.edge_free(q, q_new, s.resolution):
            return False
    return True


def _connect_selected(s: Search, tg: Tree, q_target: np.ndarray, closest: dict[int, float], b: int) -> tuple[int, bool]:
    """The strategy's goal tree steps greedily towards a new start-tree node (credited; issue #33).

    The forest's nearest node to the new node mostly lies in a tree that is shut in (a spot behind a
    barrier) when most interpretations are unreachable: asking the strategy's tree as well gives
    every goal tree its turn at the start tree, and reward-penalty keeps the one that gets closer.
    Returns (the node reached, True), else (``b``, False).
    """
    gi = s.select()
    near = tg.nearest(q_target, label=gi) if gi is not None else -1
    if near < 0:
        return b, False
    last, reached = _greedy(s, tg, near, q_target)
    if last == near:
        s.failed_from.append((1, near))
    _credit(s, gi, closest, -1.0 if last == near else s.space.distance(tg.nodes[last], q_target))
    return (last, True) if reached else (b, False)


def _credit(s: Search, gi: int, closest: dict[int, float], gap: float) -> None:
    """Reward goal sample gi's subtree for progress towards the start tree, penalise it otherwise.

    A free step that leaves the trees no closer than before (e.g. growing sideways
    inside a shelf slot) is not progress: rewarding it kept a stuck goal tree on top
    of the reward-penalty heap. ``gap`` < 0 means the step was blocked. Resampling
    waits until every goal sample is below the threshold: a goal tree that is stuck
    costs IK for new samples only when no other goal tree is making progress.
    """
    if 0.0 <= gap < closest.get(gi, np.inf):
        closest[gi] = gap
        s.reward(gi)
    else:
        s.penalize(gi, only_if_all_stuck=True)


def _extend(s: Search, tree: Tree, q_towards: np.ndarray, step: float, label: int | None = None) -> tuple[int, int]:
    """One step from the tree's nearest node (in one label's subtree if given) towards q_towards:
    (that node, or -1 if there is none; the new node, or -1 if blocked).

    A goal tree whose step is blocked tries the space's ``straight_step`` instead where it has one (a
    car: straight forwards or backwards, out of a parking bay). A car's goal tree grows out of its spot
    only towards samples roughly along the spot's axis (every curve towards the others sweeps the
    neighbours); on the fixed lot (issue #33, cover-connect, seeds 0-5, 2,000-iteration cap) it cut the
    median iterations from 69 / 791 to 21 / 183 at N = 8 / 64 and solved 5 of 6 at N = 256 (1 before).
    """
    near, q_new, _ = tree.nearest_steer(q_towards, step, label)
    if near < 0:
        return -1, -1
    new = _step(s, tree, near, q_new)
    if new < 0 and tree is not s.trees[0] and s.straight_step is not None:
        q_new = s.straight_step(tree.nodes[near], q_towards, step)
        if q_new is not None:
            new = _step(s, tree, near, q_new)
    return near, new


def _step(s: Search, tree: Tree, parent: int, q_new: np.ndarray) -> int:
    """Add q_new below ``parent`` if the step is free, else -1.

    Goal-tree steps get the full edge check. Start-tree steps are checked lazily: q_new
    and the edge's midpoint only, the rest of the edge once a path uses it (:func:`_join`).
    The start tree grows in the open, where most steps are free and most of its nodes never
    lie on the path: on fetch_boxes_3 its full edge checks were over half the collision time,
    and checking them lazily cut the median planning time by about a third (40 seeds, #19).
    Goal trees grow out of shelf slots, where a lazy edge often crosses a board: checking
    every tree lazily doubled the iterations there. The midpoint probe catches some of the
    start tree's crossings before they cost a failed join. The probes ask only whether the
    robot penetrates anything (the checker's ``config_unpadded_free`` where it has one): the
    padding is checked with the whole edge in :func:`_join`. A free probe's padded distance
    query is the larger part of its cost; without it the mean CPU time on fetch_boxes_3 fell by
    8.5 % (60 seeds, paired, interleaved; cans_1 / cans_2 within noise, +3 / -2.5 %; #19).
    """
    q_parent = tree.nodes[parent]
    if tree is not s.trees[0]:
        new = tree.add(q_new, parent) if s.edge_free(q_parent, q_new, s.resolution) else -1
        if s.blocked is not None:  # (a tree that stays its root: lazyground.planning.blocked)
            s.blocked.step(tree.labels[parent], new >= 0)
        return new
    free = s.probe_free
    if not free(q_new):
        return -1  # (most steps end blocked: the probes are computed only past a free end)
    for t in LAZY_PROBES:
        if not free(s.space.interpolate(q_parent, q_new, t)):
            return -1
    return tree.add(q_new, parent, checked=False)


def _connect(s: Search, tree: Tree, q_target: np.ndarray) -> tuple[int, bool]:
    """Greedy steps towards q_target from each of the tree's ``connect_from`` nearest nodes in turn,
    until one reaches it: (that node, True), else (the last node nearest q_target, False)."""
    nodes = tree.nearest_k(q_target, s.settings.connect_from)
    if len(nodes) <= 1:  # (a car's tree gives only its nearest node: no distances to compare)
        return _greedy(s, tree, nodes[0], q_target) if nodes else (-1, False)
    best, best_gap = -1, np.inf
    for node in nodes:
        last, reached = _greedy(s, tree, node, q_target)
        if reached:
            return last, True
        gap = s.space.distance(tree.nodes[last], q_target)
        if gap < best_gap:
            best, best_gap = last, gap
    return best, False


def _greedy(s: Search, tree: Tree, node: int, q_target: np.ndarray) -> tuple[int, bool]:
    """Greedy steps from ``node`` towards q_target: (last node, reached)."""
    while s.time_left():
        q_new, reached = tree.steer(node, q_target, s.settings.step_size)
        new = _step(s, tree, node, q_new)
        if new < 0:
            return node, False
        node = new
        if reached:
            return node, True
    return node, False


def _join(s: Search, ts: Tree, a: int, tg: Tree, b: int) -> PlanResult | None:
    """The path through start node a and goal node b (the same configuration), if it passes the fine re-check.

    The start-tree edges not checked yet are checked first, at the planner's resolution.
    A segment that fails cuts the branch below it in whichever tree it lies;
    a failing approach segment retires its goal sample.
    """
    gi = tg.labels[b]
    start_side = ts.chain(a)[::-1]  # root .. a
    goal_side = tg.chain(b)  # b .. root (the goal sample)
    path = s.with_approach(
        np.array([ts.nodes[i] for i in start_side] + [tg.nodes[j] for j in goal_side[1:]]), gi
    )
    n_start = len(start_side) - 1  # segments on the start side
    bad = _check_start_edges(s, ts, start_side, path)
    if bad < 0:
        bad = s.first_invalid_segment(path)
    if bad < 0:
        return s.result(PlanStatus.SOLVED, "", path, gi)
    if bad < n_start:
        ts.prune(start_side[bad + 1])
    elif bad < n_start + len(goal_side) - 1:
        tg.prune(goal_side[bad - n_start])
    else:
        tg.prune(goal_side[-1])
        s.retire(gi)
    return None


def _check_start_edges(s: Search, ts: Tree, start_side: list[int], path: np.ndarray) -> int:
    """Check the start-tree edges of ``path`` not checked yet (one batch): the first bad segment, or -1.

    Segment k of the path ends at start-tree node start_side[k + 1]; those before a bad one count as checked.
    """
    todo = [k for k in range(len(start_side) - 1) if not ts.checked[start_side[k + 1]]]
    bad = path_is_valid(s.space, s.checker, path, s.resolution, todo) if todo else -1
    for k in todo:
        if 0 <= bad <= k:
            break
        ts.checked[start_side[k + 1]] = True
    return bad
