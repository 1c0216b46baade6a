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


def test_equal_seeds_give_equal_selections(name):
    def run(seed):
        s, rng, out = make_strategy(name), np.random.default_rng(seed), []
        s.add(list(range(5)))
        for k in range(40):
            out.append(s.select(rng))
            s.penalize(out[-1]) if k % 2 else s.reward(out[-1])
        return out

    assert run(1) == run(1)


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
