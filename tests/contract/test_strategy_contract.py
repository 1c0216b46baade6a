"""The goal-selection strategy contract (add/select/reward/penalize/weight), run against all three strategies,
then what each one promises: the paper's reward/penalty weights, round-robin order, uniform choice."""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from lazyground.planning.strategies import STRATEGIES, StrategySettings, make_strategy


@pytest.fixture(params=sorted(STRATEGIES))
def name(request):
    return request.param


def test_selects_only_added_samples_with_weights_in_0_1(name):
    s, rng = make_strategy(name), np.random.default_rng(0)
    s.add([0, 1, 2])
    for k in range(60):
        i = s.select(rng)
        assert i in (0, 1, 2) and 0.0 < s.weight(i) <= 1.0
        s.reward(i) if k % 3 else s.penalize(i)
    s.add([3, 4])
    seen = set()
    for _ in range(60):  # new samples are selectable (each selection penalised, as a blocked extension is)
        i = s.select(rng)
        seen.add(i)
        s.penalize(i)
    assert seen >= {3, 4}
    assert all(0.0 < s.weight(i) <= 1.0 for i in range(5))


def test_new_samples_enter_at_full_weight(name):
    s = make_strategy(name)
    s.add([0, 1])
    assert s.weight(0) == s.weight(1) == 1.0


class _Reference:
    """Each strategy's promise written out plainly (no heap): the expectation the strategies are checked against."""

    def __init__(self, name):
        self.name, self.w, self.order, self.next = name, {}, [], 0

    def add(self, indices):
        self.w = {i: 0.5 for i in self.w} if self.name == "reward-penalty" else self.w
        self.w.update({i: 1.0 for i in indices})
        self.order += indices

    def select(self, rng):
        if self.name in ("reward-penalty", "cover", "cover-connect"):  # the heaviest; ties to the first added
            return max(self.order, key=lambda i: (self.w[i], -self.order.index(i)))
        if self.name == "random":
            return self.order[int(rng.integers(len(self.order)))]
        i, self.next = self.order[self.next % len(self.order)], (self.next + 1) % len(self.order)
        return i

    def reward(self, i):
        if self.name in ("reward-penalty", "cover", "cover-connect"):
            self.w[i] = 1.0 if self.w[i] >= 0.5 else self.w[i] / (1.0 - self.w[i])

    def penalize(self, i):
        if self.name in ("reward-penalty", "cover", "cover-connect"):  # cover (and cover-connect): the same weights, no reset when samples are added
            self.w[i] = self.w[i] / (self.w[i] + 1.0)
            return self.w[i] < 0.2
        return False


def test_selections_match_the_written_out_rule_under_any_outcomes(name):
    """Random rewards and penalties, on the selected sample or any other, with samples added on the way: each
    selection, weight and resampling request is the reference's (a reward that skips the heap fails here)."""
    s, ref, script = make_strategy(name), _Reference(name), np.random.default_rng(5)
    rng_s, rng_r = np.random.default_rng(9), np.random.default_rng(9)
    s.add([0, 1, 2])
    ref.add([0, 1, 2])
    for k in range(400):
        if k % 97 == 96:
            new = list(range(len(ref.order), len(ref.order) + 2))
            s.add(new)
            ref.add(new)
        got = s.select(rng_s)
        assert got == ref.select(rng_r), k
        target = got if script.random() < 0.5 else int(script.integers(len(ref.order)))
        if script.random() < 0.4:
            s.reward(target)
            ref.reward(target)
        else:
            assert s.penalize(target) == ref.penalize(target)
        if name in ("reward-penalty", "cover"):
            assert [s.weight(i) for i in ref.order] == pytest.approx([ref.w[i] for i in ref.order])


def test_unknown_strategy_is_one_clear_error():
    with pytest.raises(ValueError, match="unknown strategy 'greedy'.*reward-penalty"):
        make_strategy("greedy")


# --- reward-penalty: Hernández, Moll, Kavraki 2019, Sec. III-B/C ------------------------------------------------------

def test_reward_penalty_weights_follow_the_paper():
    s = make_strategy("reward-penalty")
    s.add([0])
    w = 1.0
    for k in range(6):  # a penalty: w / (w + 1)
        s.penalize(0)
        w = w / (w + 1.0)
        assert s.weight(0) == pytest.approx(w) == pytest.approx(1.0 / (k + 2))
    for _ in range(8):  # a reward: w / (1 - w), capped at 1
        s.reward(0)
        w = min(1.0, w / (1.0 - w)) if w < 1.0 else 1.0
        assert s.weight(0) == pytest.approx(w)
    assert s.weight(0) == 1.0


def test_reward_penalty_selects_the_heaviest_sample_ties_to_the_first_added():
    s, rng = make_strategy("reward-penalty"), np.random.default_rng(0)
    s.add([0, 1, 2])
    assert s.select(rng) == 0
    s.penalize(0)
    assert s.select(rng) == 1
    s.penalize(1)
    s.penalize(1)
    assert s.select(rng) == 2
    s.penalize(2)  # weights 1/2, 1/3, 1/2: the first added of the heaviest
    assert s.select(rng) == 0


def test_reward_penalty_asks_for_samples_below_the_threshold_and_resets_old_weights():
    s = make_strategy("reward-penalty", StrategySettings(resample_threshold=0.2, resample_weight=0.5))
    s.add([0])
    asks = [s.penalize(0) for _ in range(5)]  # weights 1/2, 1/3, 1/4, 1/5, 1/6
    assert asks == [False, False, False, False, True]
    s.add([1, 2])
    assert (s.weight(0), s.weight(1), s.weight(2)) == (0.5, 1.0, 1.0)


# --- consecutive and random ----------------------------------------------------------------------------------------

def test_consecutive_goes_round_robin_in_the_order_added():
    s, rng = make_strategy("consecutive"), np.random.default_rng(0)
    s.add([0, 1, 2])
    first = [s.select(rng) for _ in range(7)]
    assert first == [0, 1, 2, 0, 1, 2, 0]
    s.add([3])
    assert [s.select(rng) for _ in range(5)] == [1, 2, 3, 0, 1]
    assert s.penalize(1) is False and s.weight(1) == 1.0  # outcomes do not change the order


def test_random_is_uniform_and_ignores_outcomes():
    s, rng = make_strategy("random"), np.random.default_rng(0)
    s.add(list(range(4)))
    counts = Counter()
    for _ in range(4000):
        i = s.select(rng)
        counts[i] += 1
        assert s.penalize(i) is False
    assert set(counts) == {0, 1, 2, 3}
    assert all(abs(c - 1000) < 120 for c in counts.values())  # > 3.5 sigma of a binomial(4000, 1/4)
    assert all(s.weight(i) == 1.0 for i in range(4))
