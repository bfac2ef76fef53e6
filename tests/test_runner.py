"""The whole loop on the stub machine: board file, robot file, PCA9685 and HC-SR04 models, the
virtual clock. Faults from issue 3 are injected while it runs: the loop keeps running, reports
them, and no channel ever outputs a pulse outside its servo's calibrated range."""


def run_both(both_runtimes, scenario, *args):
    cp, mp = both_runtimes.call(scenario, *args)
    assert cp == mp
    return cp


def test_healthy_loop_stands_walks_and_measures(both_runtimes):
    out = run_both(both_runtimes, "scenarios.runner:healthy")
    n, held, overruns, failed, sonar_faults, dist, bad, lo, hi, mode, now = out
    assert n == 450 and held == 0 and overruns == 0 and failed == 0 and sonar_faults == 0
    assert [abs(d - (3000 + 1000 * k)) <= 2 for k, d in enumerate(dist)] == [True] * 5, dist
    assert bad == [] and 600 <= lo <= hi <= 2400
    assert mode == 4  # walking
    assert 450 * 20 <= now <= 450 * 20 + 40  # frames on their 20 ms boundaries


def test_faults_while_running(both_runtimes):
    out = run_both(both_runtimes, "scenarios.runner:faults_while_running")
    boot, back, nack, brownout, sonar, front_again, n, held, bad, mode = out
    assert nack[0] >= 1 and nack[1] in (5, 19)  # seen, retried within the frame, counted
    assert boot == (True, 20)
    assert back == (True, True)
    assert brownout == (True, True)
    faults, d_front, d_left_rear, st_front, st_left_rear = sonar
    assert faults and d_front == -1 and d_left_rear == -1
    assert st_front == 3 and st_left_rear == 2  # STUCK, NO_ECHO: never a fake distance
    assert front_again and n == 315 and mode == 4 and held == 0
    assert bad == []


def test_a_steady_frame_allocates_nothing(mp):
    """Ping + tick + two bursts, through the stub machine and the chip models, in the VM."""
    heap, n, held, failed, mode = mp.call("scenarios.runner:steady_frame_heap")
    assert (held, failed, mode) == (0, 0, 4) and n == 800
    assert heap == 0


def test_esp32_board_builds_and_runs(rt):
    # standing after the stand-up move
    assert rt.call("scenarios.runner:board_runs", "esp32_devkit", 120) == (120, 0, 0, 0, [], 3)


def test_run_counts_its_frames_from_its_own_start(both_runtimes):
    # Built, then 100 ms of boot before run(): the frames still start 20 ms apart from run's call.
    # (Counted from the build, the first wait found itself late and the second frame came at
    # once, while the first frame's bursts were still on the bus.)
    starts = run_both(both_runtimes, "scenarios.runner:run_frame_starts", 100, 4)
    assert starts == [0, 20000, 40000, 60000], starts
