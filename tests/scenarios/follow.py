"""hexapod.follow on a standing Robot fed round-robin sonar cycles: a scripted tour."""

from scenarios.rig import Rig

from hexapod import follow


def tour(ticks, form="yaw"):
    """Per side, every 50th tick: (mode, distance, angle, error, output, vx, vy, yaw, turned, walker psi)
    of a follower (in `form`) fed a wall that comes and goes, a corner ahead now and then, a fixed noise pattern."""
    out = []
    for side in ("left", "right"):
        rig = Rig()
        rig.stand()
        robot = rig.robot
        f = follow.Follower(robot)
        f.follow(side, 800, None, form)
        dist = [-1] * 5
        status = [5] * 5
        for n in range(ticks):
            k = (0, 4, 1, 3, 2)[n % 5]
            c = n // 5
            if k == 0:
                d = 3900 + (c % 40) * 100 if c % 97 < 60 else -1
            elif (k <= 2) == (side == "left"):
                d = 800 + ((c * 37) % 23) * 10 - 110 + (30 if k in (1, 3) else 0) * ((c // 13) % 3 - 1)
                if c % 151 > 140:
                    d = -1
            else:
                d = -1
            status[k] = 0 if d >= 0 else 1
            dist[k] = d
            f.update(rig.t, k, dist, status)
            rig.run(1)
            if n % 50 == 0:
                out.append(
                    (f.mode, f.distance, f.angle, f.error, f.output, f.vx, f.vy, f.yaw, f.turned, robot.walker.psi)
                )
    return out
