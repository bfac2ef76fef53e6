"""The physics render's scene: the far floor shows its checker, not black shards; the robot keeps its shadow.

The colour bounds come from the model's numbers (the floor texture's texels, the light's and
the headlight's colours), not from a rendered picture: a floor pixel in the directional light
is at least its texel x (light diffuse + light ambient + headlight ambient), whatever the
angles, since the headlight's diffuse and the speculars only add. A floor pixel shadowed by
the robot falls below that bound. One 160 x 120 frame each; skipped without offscreen GL.
"""

import numpy as np
import pytest

import robots.default as d
from hexapod_host.physics import sim as sp

REASON = sp.render_missing()
pytestmark = pytest.mark.skipif(REASON is not None, reason=REASON or "")


def standing_run():
    g, servo, physics = sp.load_robot(d)
    run = sp.Run(g, servo, physics)
    run.stand()
    return run


def lit_floor_floor(run):
    """Per channel (0..255): the darkest a floor pixel in the directional light can be."""
    mj, m = run.mj, run.model
    floor = mj.mj_name2id(m, mj.mjtObj.mjOBJ_GEOM, "floor")
    mat = m.geom_matid[floor]
    tex = m.mat_texid[mat, mj.mjtTextureRole.mjTEXROLE_RGB]
    n = m.tex_width[tex] * m.tex_height[tex] * m.tex_nchannel[tex]
    texels = m.tex_data[m.tex_adr[tex] : m.tex_adr[tex] + n].reshape(-1, m.tex_nchannel[tex])[:, :3]
    light = m.light_diffuse[0] + m.light_ambient[0] + m.vis.headlight.ambient
    return texels.min(axis=0) * m.mat_rgba[mat, :3] * light


def frame_and_floor(run, rec):
    """(RGB frame, floor pixels above the robot's highest pixel: the far floor, all floor pixels)."""
    mj = run.mj
    floor = mj.mj_name2id(run.model, mj.mjtObj.mjOBJ_GEOM, "floor")
    rec.renderer.update_scene(run.data, rec.cam)
    rgb = rec.renderer.render().astype(int)
    rec.renderer.enable_segmentation_rendering()
    seg = rec.renderer.render()[:, :, 0]  # geom id a pixel, -1 for the sky
    rec.renderer.disable_segmentation_rendering()
    robot = (seg >= 0) & (seg != floor)
    # The colour frame is multisampled, the segmentation not: a floor pixel next to the robot
    # may hold some of the robot's colour, so those are not floor here.
    near_robot = robot.copy()
    for axis in (0, 1):
        for step in (-1, 1):
            near_robot |= np.roll(robot, step, axis=axis)
    is_floor = (seg == floor) & ~near_robot
    far = is_floor.copy()
    far[np.nonzero(robot.any(axis=1))[0].min() - 1 :] = False
    return rgb, far, is_floor


def test_the_far_floor_has_no_dark_shards_and_the_robot_keeps_its_shadow(tmp_path):
    run = standing_run()
    rec = sp.Recorder(run, str(tmp_path), width=160, height=120, every=1)
    bound = lit_floor_floor(run)
    rgb, far, is_floor = frame_and_floor(run, rec)
    assert far.sum() > 3000  # a third of the frame: the test sees a real stretch of far floor
    dark = (rgb < bound).any(axis=2)
    assert int((dark & far).sum()) == 0, "far floor pixels darker than any lit floor: %d" % (dark & far).sum()
    assert (dark & is_floor).sum() > 200  # the robot's shadow under it
    # 1.5 m from where the light was placed: the light follows the robot, so the shadow does too.
    run.data.qpos[:2] += (1.5, 0.8)
    run.mj.mj_forward(run.model, run.data)
    rgb, far, is_floor = frame_and_floor(run, rec)
    dark = (rgb < bound).any(axis=2)
    assert int((dark & far).sum()) == 0
    assert (dark & is_floor).sum() > 200
    rec.finish()
