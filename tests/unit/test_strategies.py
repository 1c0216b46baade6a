"""The reward-penalty heap arithmetic and each strategy's order, pinned exactly."""

import numpy as np
import pytest

from lazyground.planning.strategies import (
    STRATEGIES,
    Consecutive,
    Random,
    RewardPenalty,
    StrategySettings,
    make_strategy,
    penalty_weight,
    reward_weight,
)


def test_weight_formulas_match_the_paper():
    assert penalty_weight(1.0) == pytest.approx(0.5)
    assert penalty_weight(0.5) == pytest.approx(1 / 3)
    assert reward_weight(1 / 3) == pytest.approx(0.5)
    assert reward_weight(0.25) == pytest.approx(1 / 3)
    assert reward_weight(0.5) == 1.0  # 0.5 / 0.5 = 1
    assert reward_weight(0.9) == 1.0  # w/(1-w) = 9: capped at 1


def test_scripted_run_of_rewards_and_penalties():
    rp = RewardPenalty()
    rng = np.random.default_rng(0)
    rp.add([0, 1, 2])
    assert rp.select(rng) == 0  # all at 1.0: the first added wins ties
    assert rp.penalize(0) is False
    assert rp.weight(0) == pytest.approx(0.5)
    assert rp.select(rng) == 1
    rp.reward(1)  # 1.0 stays 1.0
    assert rp.weight(1) == 1.0 and rp.select(rng) == 1
    assert rp.penalize(1) is False and rp.penalize(2) is False
    # all at 0.5 now: index order breaks the tie
    assert [rp.weight(i) for i in range(3)] == pytest.approx([0.5, 0.5, 0.5])
    assert rp.select(rng) == 0
    weights = []
    for _ in range(3):
        rp.penalize(0)
        weights.append(rp.weight(0))
    assert weights == pytest.approx([1 / 3, 1 / 4, 1 / 5])
    assert rp.select(rng) == 1
    rp.reward(0)  # 0.2 -> 0.25
    assert rp.weight(0) == pytest.approx(0.25)
    rp.penalize(0)  # 0.25 -> 0.2, not below the threshold
    assert rp.weight(0) == pytest.approx(0.2)


def test_resampling_trigger_and_reset():
    rp = RewardPenalty(StrategySettings(resample_threshold=0.2))
    rp.add([0, 1])
    outcomes = [rp.penalize(0) for _ in range(5)]  # 1 -> 1/2 -> 1/3 -> 1/4 -> 1/5 -> 1/6
    assert outcomes == [False, False, False, False, True]
    assert rp.weight(0) == pytest.approx(1 / 6)
    rp.add([2, 3])  # the planner's resampling: new at 1.0, all old reset to 0.5
    assert [rp.weight(i) for i in range(4)] == pytest.approx([0.5, 0.5, 1.0, 1.0])
    rng = np.random.default_rng(0)
    assert rp.select(rng) == 2
    rp.penalize(2)
    assert rp.select(rng) == 3
    rp.penalize(3)
    assert rp.select(rng) == 0  # now every sample is at 0.5: the oldest first


def test_max_heap_order_follows_weights():
    rp = RewardPenalty()
    rp.add(list(range(5)))
    for i, n in zip(range(5), (3, 1, 4, 0, 2)):
        for _ in range(n):
            rp.penalize(i)
    order = []
    rng = np.random.default_rng(0)
    for _ in range(5):
        top = rp.select(rng)
        order.append(top)
        for _ in range(10):  # push it to the bottom
            rp.penalize(top)
    assert order == [3, 1, 4, 0, 2]


def test_consecutive_is_round_robin_in_draw_order():
    c = Consecutive()
    c.add([0, 1, 2])
    rng = np.random.default_rng(0)
    assert [c.select(rng) for _ in range(5)] == [0, 1, 2, 0, 1]
    c.add([3])
    assert [c.select(rng) for _ in range(4)] == [2, 3, 0, 1]
    assert c.penalize(0) is False  # never asks for resampling


def test_random_is_uniform_and_seeded():
    """The draw is the generator's next integer below the number of samples, in the order added."""
    r = Random()
    r.add([4, 7, 9, 2])
    want = [[4, 7, 9, 2][k] for k in np.random.default_rng(7).integers(0, 4, size=1)]  # one draw per select
    rng = np.random.default_rng(7)
    assert [r.select(rng)] == want
    rng = np.random.default_rng(1)
    counts = np.bincount([r.select(rng) for _ in range(4000)], minlength=10)[[4, 7, 9, 2]]
    assert counts.min() > 850 and counts.max() < 1150 and counts.sum() == 4000


def test_registry_by_name():
    assert set(STRATEGIES) == {"reward-penalty", "consecutive", "random", "cover", "cover-connect"}
    assert isinstance(make_strategy("random"), Random)
    with pytest.raises(ValueError, match="unknown strategy 'greedy'"):
        make_strategy("greedy")
