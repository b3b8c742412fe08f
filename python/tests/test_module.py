"""The Python module against the command line (the same bytes), against values computed by hand,
against exact invariants between its buffers, and against the ray-cast oracle."""
import math
import re
import subprocess
import threading
import time

import numpy as np
import pytest

import shadowref

SMALL = (96, 72)


def test_readme_line():
    frame = shadowref.render("scenes/room.yaml")
    scene = shadowref.load("scenes/room.yaml")
    assert frame.stencil.dtype == np.uint8
    assert frame.stencil.shape == (scene.height, scene.width)
    # The room's one light casts shadows: some pixel of the last volume pass counts one or more.
    assert frame.stencil.max() >= 1


def test_buffers_are_views_of_the_renderer_s_memory():
    frame = shadowref.render("scenes/minimal.yaml", size=SMALL)
    for array in (frame.color, frame.depth, frame.eye_depth, frame.stencil):
        assert not array.flags.owndata  # a view of the vector the renderer filled, not a copy
        assert not array.flags.writeable
        assert array.base is not None
    assert frame.color.shape == (SMALL[1], SMALL[0], 4) and frame.color.dtype == np.float32
    assert frame.depth.dtype == np.float32 and frame.eye_depth.dtype == np.float64
    # Arrays outlive the Frame: the capsule owns the memory.
    stencil = frame.stencil
    del frame
    assert stencil.shape == (SMALL[1], SMALL[0])


def parse_region(text):
    """The --dump-region grids: {light: {(x, y): count}}."""
    grids, light, xs = {}, None, []
    for line in text.splitlines():
        if line.startswith("light "):
            light = line[len("light "):].rstrip(":")
            grids[light] = {}
        elif line.startswith("y\\x"):
            xs = [int(v) for v in line.split()[1:]]
        elif line.strip() and not line.startswith("stencil "):
            values = [int(v) for v in line.split()]
            for x, count in zip(xs, values[1:]):
                grids[light][(x, values[0])] = count
    return grids


@pytest.mark.parametrize("method", ["zpass", "zfail"])
def test_stencil_counts_are_the_command_line_s(cli, method, tmp_path):
    # The pumpkins: the camera stands inside a volume, so z-pass counts -1 where z-fail counts 0.
    w, h = 80, 60
    out = subprocess.run([cli, "render", "scenes/pumpkins.yaml", "--method", method, "-D", f"image.width={w}",
                          "-D", f"image.height={h}", "--dump-region", f"0,0,{w},{h}", "--stencil-view", "signed",
                          "--quiet", "-o",
                          str(tmp_path / "a.png")], capture_output=True, text=True, check=True)
    grids = parse_region(out.stdout)
    assert grids, out.stdout + out.stderr
    frame = shadowref.render("scenes/pumpkins.yaml", method=method, size=(w, h), threads=2)
    assert sorted(grids) == sorted(frame.stencil_per_light)
    for light, grid in grids.items():
        counts = frame.stencil_per_light[light].view(np.int8)  # signed, as the grid prints them
        assert len(grid) == w * h
        assert all(counts[y, x] == c for (x, y), c in grid.items())


def test_same_exr_as_the_command_line(cli, tmp_path):
    args = ["-D", f"image.width={SMALL[0]}", "-D", f"image.height={SMALL[1]}"]
    subprocess.run([cli, "render", "scenes/two_lights.yaml", "--method", "zpass", "--threads", "3", *args, "--quiet",
                    "-o", str(tmp_path / "cli.exr")], check=True)
    frame = shadowref.render("scenes/two_lights.yaml", method="zpass", threads=1, size=SMALL,
                             stencil_per_light=False, visibility=False)
    frame.write(tmp_path / "py.exr")
    # compare: every channel (R, G, B, A, Z, stencil) with tolerance 0; exit 0 only when equal.
    result = subprocess.run([cli, "compare", str(tmp_path / "cli.exr"), str(tmp_path / "py.exr")],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


def test_png_holds_the_colour_rounded_to_8_bits(tmp_path):
    image = pytest.importorskip("matplotlib.image")
    frame = shadowref.render("scenes/minimal.yaml", size=SMALL)
    frame.write(tmp_path / "a.png")
    png = np.round(image.imread(str(tmp_path / "a.png")) * 255).astype(np.uint8)
    # round(c * 255) after clamping, halves up; the file's top row is the frame's last.
    expected = np.floor(np.clip(frame.color[..., :3].astype(np.float64), 0, 1) * 255 + 0.5).astype(np.uint8)
    assert np.array_equal(png[..., :3], expected[::-1])


def test_both_pipelines_and_any_thread_count_give_the_same_bytes():
    frames = [shadowref.render("scenes/minimal.yaml", method="zfail", size=SMALL, pipeline="reference")] + \
             [shadowref.render("scenes/minimal.yaml", method="zfail", size=SMALL, threads=t) for t in (1, 2, 3)]
    for frame in frames[1:]:
        for name in ("color", "depth", "stencil"):
            assert getattr(frame, name).tobytes() == getattr(frames[0], name).tobytes(), name


def test_two_threads_render_at_once_and_release_the_gil():
    scene = shadowref.load("scenes/room.yaml", {"image.width": 320, "image.height": 240})
    serial = shadowref.render(scene, method="zfail", threads=1).color.tobytes()

    def attempt():
        spans, results = {}, {}

        def work(name):
            start = time.perf_counter()
            results[name] = shadowref.render(scene, method="zfail", threads=1, pipeline="reference").color.tobytes()
            spans[name] = (start, time.perf_counter())

        workers = [threading.Thread(target=work, args=(n,)) for n in ("a", "b")]
        ticks = []
        for t in workers:
            t.start()
        while any(t.is_alive() for t in workers):
            ticks.append(time.perf_counter())
        for t in workers:
            t.join()
        assert results["a"] == serial and results["b"] == serial
        # The longest stretch of a render during which this thread did not run, as a share of the
        # render: a render holding the GIL would stop this thread for all of it (close to 1).
        start, end = spans["a"]
        inside = [start] + [t for t in ticks if start < t < end] + [end]
        return max(b - a for a, b in zip(inside, inside[1:])) / (end - start)

    # Three tries, so that a busy machine's scheduler cannot fail it; holding the GIL fails all three.
    stalls = []
    for _ in range(3):
        stalls.append(attempt())
        if stalls[-1] < 0.5:
            break
    assert min(stalls) < 0.5, stalls


CAMERA_OVER_PLANE = {
    "image": {"width": 33, "height": 33},
    "camera": {"eye": [0, 4, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 40, "near": 0.5, "far": 20},
    "lights": [{"name": "sun", "position": [0, 6, 0]}],
    "meshes": {"ground": {"plane": {"size": [40, 40]}}},
    "nodes": [{"name": "ground", "mesh": "ground"}],
}


@pytest.mark.parametrize("method, far", [("none", 20), ("zfail", "infinite")])
def test_eye_depth_is_the_distance_along_the_view_axis(method, far):
    # The centre pixel of an odd-sized image looks along the axis, at the origin on the ground,
    # |eye - target| = sqrt(4^2 + 3^2) = 5 away.
    scene = dict(CAMERA_OVER_PLANE, camera=dict(CAMERA_OVER_PLANE["camera"], far=far))
    frame = shadowref.render(scene, method=method)
    assert frame.eye_depth[16, 16] == pytest.approx(5.0, rel=1e-4)
    # Window depth of a point 5 away: with the finite frustum (f + n)/(f - n) - 2fn/((f - n) z),
    # with P_inf 1 - 2n/z ([Kuhn 2016, §3.3]), each mapped from [-1, 1] to [0, 1].
    n, f = 0.5, 20.0
    ndc = (f + n) / (f - n) - 2 * f * n / ((f - n) * 5) if far != "infinite" else 1 - 2 * n / 5
    assert frame.depth[16, 16] == pytest.approx((ndc + 1) / 2, abs=1e-6)
    # The top row sees beyond the plane's far edge when the plane is finite... here it is 40 wide:
    # every pixel shows it, so no eye depth is infinite.
    assert np.isfinite(frame.eye_depth).all()


def test_dict_scene_is_the_same_as_its_yaml_text():
    import json
    a = shadowref.render(CAMERA_OVER_PLANE, method="zpass")
    b = shadowref.render(shadowref.loads(json.dumps(CAMERA_OVER_PLANE)), method="zpass")
    assert a.color.tobytes() == b.color.tobytes()


def test_errors_carry_file_line_and_column(tmp_path):
    with pytest.raises(shadowref.SceneError) as e:
        shadowref.loads("image:\n  width: banana\n", name="bad.yaml")
    assert (e.value.file, e.value.line) == ("bad.yaml", 2)
    assert e.value.column >= 1 and str(e.value).startswith("bad.yaml:2:")
    with pytest.raises(shadowref.SceneError) as e:
        shadowref.load("scenes/minimal.yaml", ["image.width=banana"])
    assert (e.value.file, e.value.line, e.value.column) == ("<command line>", 1, 13)
    with pytest.raises(shadowref.SceneError) as e:
        shadowref.load(dict(CAMERA_OVER_PLANE, colour=1))
    assert e.value.file == "<dict>" and e.value.line is not None
    bad = tmp_path / "bad.yaml"
    bad.write_text("image: {width: 64}\nshadow: {method: nope}\n")
    with pytest.raises(shadowref.SceneError) as e:
        shadowref.load(bad)
    assert (e.value.file, e.value.line) == (str(bad), 2)
    with pytest.raises(shadowref.SceneError):
        shadowref.render("scenes/minimal.yaml", method="nope", size=SMALL)
    with pytest.raises(shadowref.SceneError):
        shadowref.render("scenes/minimal.yaml", pipeline="gpu", size=SMALL)
    with pytest.raises(shadowref.SceneError):
        shadowref.render("scenes/minimal.yaml", history=(SMALL[0], 0), size=SMALL)
    with pytest.raises(shadowref.SceneError):
        shadowref.render("scenes/minimal.yaml", size=SMALL).write(tmp_path / "a.tiff")
    assert not (tmp_path / "a.tiff").exists()
    assert isinstance(e.value, ValueError)


def test_pixel_history_is_the_command_line_s(cli, tmp_path):
    # README.md: at 400,220 under the table, z-fail counts the table top's volume behind the floor.
    frame = shadowref.render("scenes/room.yaml", method="zfail", history=(400, 220))
    back = [r for r in frame.history if r.draw == 41 and not r.front]
    assert [(r.what, r.depth_passed, r.stencil_before, r.stencil_after) for r in back] == \
        [("volume side, object 'room/table/top'", False, 0, 1)]
    last = frame.history[-1]
    assert (last.draw, last.what, last.stencil_passed, last.stencil_after) == (92, "lit pass, object 'room/floor'", False, 1)
    out = subprocess.run([cli, "render", "scenes/room.yaml", "--method", "zfail", "--pixel-history", "400,220",
                          "-o", str(tmp_path / "a.png")], capture_output=True, text=True, check=True)
    # The command line also names the light of each volume and lit-pass fragment ("light L0"); the
    # library's record does not carry the light, so the label is set aside for the comparison.
    lines = [line.strip() for line in (out.stdout + out.stderr).splitlines() if line.lstrip().startswith("draw ")]
    assert any("  light L0  " in line for line in lines)
    assert [re.sub(r"  light L\d+  ", "  ", line) for line in lines] == [repr(r) for r in frame.history]


def test_visibility_of_a_volume_method_is_where_the_count_is_zero():
    frame = shadowref.render("scenes/two_lights.yaml", method="zfail", size=SMALL)
    assert list(frame.visibility) == shadowref.load("scenes/two_lights.yaml").lights
    for (light, vis), counts in zip(frame.visibility.items(), frame.stencil_per_light.values()):
        assert np.array_equal(vis, (counts == 0).astype(np.float32)), light
        assert 0 < vis.mean() < 1  # each light casts some shadow and lights something


def test_statistics():
    none = shadowref.render("scenes/minimal.yaml", method="none", size=SMALL)
    zpass = shadowref.render("scenes/minimal.yaml", method="zpass", size=SMALL)
    assert none.stencil is None and none.stats["stencil_writes"] == 0
    assert zpass.stats["stencil_writes"] > 0
    for s in (none.stats, zpass.stats):
        assert s["draw_calls"] > 0 and s["fragments"] >= s["color_writes"] > 0
        assert s["triangles_in"] >= s["triangles_culled"]
    assert all(ms >= 0 for ms in zpass.pass_milliseconds.values())


def test_shadow_maps():
    frame = shadowref.render("scenes/minimal.yaml", method="shadowmap", size=SMALL,
                             overrides={"shadow.map_size": 128})
    # The bulb is a point light: a cube of six maps.
    assert list(frame.shadow_maps) == [f"L0.face{i}" for i in range(6)]
    for depth in frame.shadow_maps.values():
        assert depth.shape == (128, 128) and depth.dtype == np.float32
        assert 0 <= depth.min() and depth.max() <= 1
    # The face looking down (-y) sees the box nearer than the ground around it.
    down = frame.shadow_maps["L0.face3"]
    assert down.min() < down.max()
    assert frame.stencil is None and not frame.stencil_per_light


def test_oracle_agrees_off_the_edges():
    scene = shadowref.load("scenes/minimal.yaml", {"image.width": 64, "image.height": 48})
    frame = shadowref.render(scene, method="zfail")
    truth = shadowref.oracle(scene, "bulb", threads=2)
    inside = (truth.near_edge == 0) & (truth.hit == 1)
    assert inside.sum() > 0.3 * inside.size  # the ground and the box, away from their outlines
    assert np.array_equal(frame.stencil_per_light["L0"][inside], truth.zfail[inside])
    assert np.array_equal(frame.visibility["bulb"][inside], truth.lit[inside].astype(np.float32))
    assert 0 < truth.lit[inside].mean() < 1


def test_docs_quote_the_golden_example_as_it_is():
    from conftest import ROOT
    page = (ROOT / "docs" / "python.md").read_text()
    marker = "<!-- python/tests/test_golden_example.py -->\n```python\n"
    start = page.index(marker) + len(marker)
    assert page[start:page.index("```\n", start)] == (ROOT / "python/tests/test_golden_example.py").read_text()


def test_per_light_buffers_are_bounded_before_rendering():
    # 2 lights x 6000 x 6000 = 7.2e7 visibility values > 2^26; with the first light soft (itself and
    # 8 around it) 10 x 3.6e7 stencil counts > 2^27.
    big = {"image.width": 6000, "image.height": 6000}
    start = time.perf_counter()
    with pytest.raises(shadowref.SceneError, match=r"^visibility: 2 lights x 6000x6000 values is more than"):
        shadowref.render("scenes/two_lights.yaml", overrides=big, method="zpass", shadow_maps=False)
    with pytest.raises(shadowref.SceneError, match=r"^stencil per light: 10 lights x 6000x6000"):
        shadowref.render("scenes/two_lights.yaml", overrides=dict(big, **{"lights.0.soft.shape": "square_y"}),
                         method="zpass", visibility=False)
    assert time.perf_counter() - start < 5  # refused before anything the size of the image was made
