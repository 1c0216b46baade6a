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
    assert cover.startswith("| rack-panda | 64 | 1 | Cover (bidirectional) | 10 | 8 | 8 | 1.35 | 1.35 | ")
    two_sided, faster = (float(x) for x in cover.split("|")[-3:-1])
    assert two_sided < 0.001 and faster < two_sided  # every cover run faster than every round-robin run
    assert next(line for line in text.splitlines() if "Consecutive" in line).endswith("| 7 | 5.98 | 5.45 |  |  |")  # the timeout at its 10 s limit
    slower = sweep_tests(slow + [_row(f"rack_panda_64_1_s{s}", "cover", "solved", 9.0) for s in range(8)])
    assert float(next(line for line in slower.splitlines() if "Cover" in line).split("|")[-2]) > 0.99  # not faster


def _baseline(scene, status, t, limit):
    return dict(scene=scene, planner="nearest-first-bidirectional", strategy="consecutive", status=status, time_s=str(t),
                time_limit=str(limit))


def test_a_method_with_another_time_limit_gets_no_p_and_the_table_says_its_limit():
    from lazyground.bench.sweep import sweep_tests

    rows = [_row("lot_64_2_0_576", s, "solved", 1.0 + i) for i in range(3) for s in ("cover-connect", "consecutive")]
    rows += [_baseline("lot_64_2_0_576", "solved", 30.0 + i, 60) for i in range(3)]
    line = next(x for x in sweep_tests(rows).splitlines() if "nearest-first" in x)
    assert line.endswith("| 60 | 3 | 3 | 31.00 | 31.00 |  |  |")
    assert "| nearest-first-bidirectional, 60 s limit | 31.00 (100% of 3) |" in sweep_table(rows)


def test_ratios_are_bounds_where_unsolved_runs_censor_a_median():
    from lazyground.bench.sweep import censored_median, sweep_ratios

    ours = [_row("lot_64_2_0_576", "cover-connect", "solved", t) for t in (2.0, 3.0, 4.0)]
    assert censored_median(ours) == (3.0, True)
    censored = [_baseline("lot_64_2_0_576", "timeout", 60.0, 60) for _ in range(2)] + [_baseline("lot_64_2_0_576", "solved", 50.0, 60)]
    assert censored_median(censored) == (60.0, False)
    line = next(x for x in sweep_ratios(ours + censored).splitlines() if "nearest-first" in x)
    assert line.endswith("| 3.00 | >= 60.00 | >= 20.0x |")  # the baseline's median is only a lower bound
    slow_ours = [_row("lot_64_2_0_576", "cover-connect", "timeout", 10.0) for _ in range(3)]
    solved = [_baseline("lot_64_2_0_576", "solved", t, 60) for t in (20.0, 30.0, 40.0)]
    assert sweep_ratios(slow_ours + solved).splitlines()[-1].endswith("| >= 10.00 | 30.00 | <= 3.0x |")
    assert sweep_ratios(slow_ours + censored).splitlines()[-1].endswith("| unknown (both censored) |")
    assert sweep_ratios(ours) == ""  # no baseline rows
