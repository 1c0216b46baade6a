"""The family sweep's table (issue #33): medians with unsolved runs at the limit, success rates, N or k on the axis."""

from lazyground.bench.sweep import size_of, sweep_keys, sweep_table


def _row(scene, strategy, status, t):
    return dict(scene=scene, planner="lazyground-bidirectional", strategy=strategy, status=status, time_s=str(t), time_limit="10")


def test_sizes_and_keys():
    assert size_of("lot_256_2") == ("lot", 256, 2) and size_of("rack_panda_64_1_s3") == ("rack-panda", 64, 1)
    assert size_of("parking_1") is None
    assert sweep_keys("lot", [8, 64]) == ["lot:8:2", "lot:64:2"]
    assert sweep_keys("lot-fixed", [8]) == ["lot:8:2:0:576"]
    assert size_of("lot_8_2_0_576") == size_of("lot_8_2_s0_of576") == ("lot-fixed", 8, 2)
    assert size_of("lot_8_2_0") == size_of("lot_8_2_s0") == ("lot", 8, 2)


def test_table_counts_unsolved_at_the_limit():
    rows = [_row("lot_8_2", "cover", "solved", 1.0), _row("lot_8_2", "cover", "timeout", 10.0), _row("lot_8_2", "cover", "solved", 2.0),
            _row("lot_64_2", "cover", "timeout", 10.0)]
    text = sweep_table(rows)
    assert "**lot, k=2**" in text and "| N=8 | N=64 |" in text
    assert "| Cover (bidirectional) | 2.00 (67% of 3) | 10.00 (0% of 1) |" in text


def test_each_method_is_tested_against_round_robin_per_size_over_layouts():
    from lazyground.bench.sweep import sweep_tests

    fast = [_row(f"rack_panda_64_1_s{s}", "cover", "solved", 1.0 + s / 10) for s in range(8)]
    slow = [_row(f"rack_panda_64_1_s{s}", "consecutive", "solved" if s else "timeout", 5.0 + s / 10) for s in range(8)]
    text = sweep_tests(fast + slow)
    cover = next(line for line in text.splitlines() if "Cover" in line)
    assert cover.startswith("| rack-panda | 64 | 1 | Cover (bidirectional) | 8 | 8 | 1.35 | 1.35 | ")
    assert float(cover.split("|")[-2]) < 0.001  # every cover run faster than every round-robin run
    assert next(line for line in text.splitlines() if "Consecutive" in line).endswith("| 7 | 5.98 | 5.45 |  |")  # the timeout at its 10 s limit
