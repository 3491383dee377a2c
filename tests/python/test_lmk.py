# SPDX-License-Identifier: BSD-3-Clause
"""`import lmk` (issue #36): clouds as numpy arrays, landmarks, and searches that give exactly what
the CLI gives on the same files. Run by ctest (tests/CMakeLists.txt), which sets PYTHONPATH to the
build tree's package, LMK_BINARY to the CLI and LMK_CLI_FIXTURES to tests/cli/fixtures."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import lmk

LMK = os.environ["LMK_BINARY"]
CUP = os.path.join(os.environ["LMK_CLI_FIXTURES"], "cup_v2.lmk")


def run(*args):
    return subprocess.run([LMK, *args], check=True, capture_output=True, text=True).stdout


@pytest.fixture(scope="module")
def tabletop(tmp_path_factory):
    """The built-in tabletop frame (`lmk gen`), where cup_v2.lmk was captured."""
    path = str(tmp_path_factory.mktemp("scene") / "tab.pcd")
    run("gen", path)
    return path


def without_arrays(match):
    return {k: v for k, v in match.items() if k not in ("pose", "box")}


def test_version_is_the_cli_s():
    assert lmk.__version__ in run("--version")


def test_find_gives_exactly_lmk_find_json(tabletop):
    cli = json.loads(run("find", tabletop, CUP, "--rejected", "--json", "-"))
    got = lmk.find(lmk.read_cloud(tabletop), lmk.load_landmark(CUP), rejected=True)
    assert len(got["matches"]) > 0
    assert [without_arrays(m) for m in got["matches"]] == cli["matches"]
    assert [without_arrays(m) for m in got["rejected"]] == cli["rejected"]
    assert got["stats"]["rejections"] == cli["stats"]["rejections"]
    for m in got["matches"]:
        assert m["pose"].shape == (4, 4) and m["box"]["pose"].shape == (4, 4)
        # The box is the landmark's capture box moved by the pose.
        np.testing.assert_allclose(m["box"]["pose"][:3, 3], m["position"], atol=1e-12)
        # Every match says how sure it is (a calibrated probability) and what competes with it.
        assert 0.0 <= m["confidence"]["probability"] <= 1.0
        assert "competitor" in m["confidence"]


def test_error_metrics_are_listed_with_their_units():
    metrics = {m["name"]: m for m in lmk.error_metrics()}
    assert list(metrics)[:6] == ["paper", "rapid", "vdb", "visibility", "projective", "sensor"]
    assert metrics["visibility"]["error_unit"] == "m"
    assert metrics["sensor"]["error_unit"] == "sd" and metrics["sensor"]["noise_normalised"]
    assert metrics["visibility"]["prune_bound"] == pytest.approx(0.015)


def test_a_metric_from_a_plugin_runs_through_find(tabletop):
    """A metric only the tests know (tests/metric_plugin), named in $LMK_METRIC_PLUGINS: listed and
    searched with from Python, in a fresh interpreter, as a user's own would be."""
    script = (
        "import json, lmk, sys\n"
        "names = [m['name'] for m in lmk.error_metrics()]\n"
        "found = lmk.find(lmk.read_cloud(sys.argv[1]), lmk.load_landmark(sys.argv[2]),"
        " metric='nearest')\n"
        "print(json.dumps({'names': names, 'metric': found['stats']['metric'],"
        " 'unit': found['error_unit'], 'errors': [m['error'] for m in found['matches']]}))\n")
    env = dict(os.environ, LMK_METRIC_PLUGINS=os.environ["LMK_TEST_METRIC_PLUGIN"])
    out = json.loads(subprocess.run([sys.executable, "-c", script, tabletop, CUP], check=True,
                                    capture_output=True, text=True, env=env).stdout)
    assert out["names"][-1] == "nearest" and out["metric"] == "nearest" and out["unit"] == "m"
    assert len(out["errors"]) > 0 and all(e < 0.004 for e in out["errors"])


def test_settings_are_the_flags_with_their_units_and_checks(tabletop):
    scene, cup = lmk.read_cloud(tabletop), lmk.load_landmark(CUP)
    cli = json.loads(run("find", tabletop, CUP, "--max-tilt", "30", "--no-refine", "--json", "-"))
    got = lmk.find(scene, cup, max_tilt=30, refine=False)
    assert [without_arrays(m) for m in got["matches"]] == cli["matches"]
    assert "max_tilt" in lmk.find_setting_keys()
    with pytest.raises(ValueError, match="max-tilt"):
        lmk.find(scene, cup, max_tilt=500)
    with pytest.raises(ValueError, match="unknown setting 'colour-weigh'"):
        lmk.find(scene, cup, colour_weigh=1)


def test_an_organised_numpy_cloud_finds_what_its_pcd_finds(tabletop):
    read = lmk.read_cloud(tabletop)
    assert read.organised and read.points.shape == (480, 640, 3)
    assert not read.points.flags.writeable  # a view over the cloud's memory
    built = lmk.Cloud(read.points.copy(), sensor_pose=read.sensor_pose)
    cup = lmk.load_landmark(CUP)
    a, b = lmk.find(read, cup), lmk.find(built, cup)
    assert [without_arrays(m) for m in a["matches"]] == [without_arrays(m) for m in b["matches"]]
    # float64 is taken too, and N x 3 is an unorganised cloud.
    flat = lmk.Cloud(read.points.reshape(-1, 3).astype(np.float64))
    assert not flat.organised and len(flat) == 480 * 640


def test_bad_arrays_are_value_errors_that_name_them():
    with pytest.raises(ValueError, match="points: must be an N x 3 array"):
        lmk.Cloud(np.zeros((5, 2), dtype=np.float32))
    with pytest.raises(ValueError, match="points: must be an array of float32 or float64"):
        lmk.Cloud(np.zeros((5, 3), dtype=np.int32))
    with pytest.raises(ValueError, match="colours: must have the points' shape"):
        lmk.Cloud(np.zeros((5, 3), dtype=np.float32), colours=np.zeros((4, 3), dtype=np.uint8))
    pose = np.eye(4)
    pose[0, 3] = np.nan
    with pytest.raises(ValueError, match="sensor_pose: must be finite"):
        lmk.Cloud(np.zeros((5, 3), dtype=np.float32), sensor_pose=pose)
    with pytest.raises(ValueError, match="sensor_pose: must be a 4 x 4 array"):
        lmk.Cloud(np.zeros((5, 3), dtype=np.float32), sensor_pose=np.eye(3))


def test_fused_frames_find_what_one_frame_finds(tabletop):
    """Two frames of the tabletop fused (lmk.fuse, as `lmk find A.pcd B.pcd`) hold the cup where
    the frame alone does; poses move each frame into the common frame."""
    scene, cup = lmk.read_cloud(tabletop), lmk.load_landmark(CUP)
    alone = lmk.find(scene, cup)["matches"][0]["position"]
    fused = lmk.fuse([scene, scene])
    assert fused.organised and fused.points.shape == scene.points.shape
    np.testing.assert_allclose(lmk.find(fused, cup)["matches"][0]["position"], alone, atol=0.01)
    moved = np.eye(4)
    moved[:3, 3] = [1.0, 2.0, 0.0]
    elsewhere = lmk.fuse([scene, scene], poses=[moved, moved])
    np.testing.assert_allclose(lmk.find(elsewhere, cup)["matches"][0]["position"],
                               np.asarray(alone) + [1.0, 2.0, 0.0], atol=0.01)
    with pytest.raises(ValueError, match="1 poses for 2 clouds"):
        lmk.fuse([scene, scene], poses=[moved])
    flat = lmk.Cloud(scene.points.reshape(-1, 3))
    with pytest.raises(lmk.Error, match="frame 2: an unorganised cloud"):
        lmk.fuse([scene, flat])


def test_capture_saves_and_loads_with_its_verdict(tabletop, tmp_path):
    scene, cup = lmk.read_cloud(tabletop), lmk.load_landmark(CUP)
    box = cup.box
    landmark, verdict = lmk.capture(scene, box["pose"], box["size"], name="cup")
    assert landmark.name == "cup" and landmark.view_count == 1
    # `lmk capture` of the same box writes the same points.
    rotation = box["pose"][:3, :3]
    w = np.sqrt(max(0.0, 1.0 + np.trace(rotation))) / 2.0
    quaternion = [w, (rotation[2, 1] - rotation[1, 2]) / (4 * w),
                  (rotation[0, 2] - rotation[2, 0]) / (4 * w),
                  (rotation[1, 0] - rotation[0, 1]) / (4 * w)]
    box_json = tmp_path / "box.json"
    box_json.write_text(json.dumps({"position": box["pose"][:3, 3].tolist(),
                                    "quaternion": quaternion, "size": box["size"].tolist()}))
    run("capture", tabletop, "--box-json", str(box_json), "--name", "cup", "-o",
        str(tmp_path / "cli.lmk"), "--no-check")
    np.testing.assert_array_equal(landmark.points,
                                  lmk.load_landmark(str(tmp_path / "cli.lmk")).points)
    assert verdict["found_itself"]
    assert set(verdict) == {"distinctive", "found_itself", "other_instances", "slides", "findings"}
    # What the capture check found travels with the landmark (issue #59).
    assert verdict["findings"]["look_alike_checked"]
    assert landmark.capture_findings["look_alikes"] == verdict["findings"]["look_alikes"]
    # The grids: free space inside the box, and the distance field zero on the points.
    assert landmark.empty_space.shape[1] == 3 and len(landmark.empty_space) > 0
    assert np.all(landmark.distance(landmark.points) < 0.005)
    assert landmark.distance(landmark.points + [0.0, 0.0, 1.0]).min() > 0.005
    path = str(tmp_path / "cup.lmk")
    landmark.save(path)
    np.testing.assert_array_equal(lmk.load_landmark(path).points, landmark.points)
    with pytest.raises(ValueError, match="box: sides must be positive"):
        lmk.capture(scene, box["pose"], [0.1, 0.0, 0.1], name="flat")
    # Capture settings as keywords, as `lmk capture`'s flags: a coarser leaf keeps fewer points.
    coarse, _ = lmk.capture(scene, box["pose"], box["size"], name="cup", leaf_size=0.01,
                            check=False)
    assert 0 < len(coarse.points) < len(landmark.points)
    with pytest.raises(ValueError, match=r"leaf_size \(--leaf-size\): 1e-05 must be finite"):
        lmk.capture(scene, box["pose"], box["size"], name="cup", leaf_size=1e-5)
    with pytest.raises(ValueError, match="unknown setting 'leafsize'"):
        lmk.capture(scene, box["pose"], box["size"], name="cup", leafsize=0.01)
    with pytest.raises(lmk.Error, match="no scene point inside the box"):
        far = box["pose"].copy()
        far[:3, 3] += 100.0
        lmk.capture(scene, far, box["size"], name="nowhere")


def test_lmk_errors_keep_the_cli_s_one_line_message(tmp_path):
    missing = str(tmp_path / "missing.lmk")
    with pytest.raises(lmk.Error) as error:
        lmk.load_landmark(missing)
    assert missing in str(error.value) and "\n" not in str(error.value)
    assert issubclass(lmk.Error, RuntimeError)


def test_progress_hears_every_seed(tabletop):
    seen = []
    got = lmk.find(lmk.read_cloud(tabletop), lmk.load_landmark(CUP),
                   progress=lambda done, total: seen.append((done, total)))
    # In order, once per seed, although the reports come from the search's threads.
    seeds = got["stats"]["seeds"]
    assert seen == [(done, seeds) for done in range(1, seeds + 1)]


def test_the_gil_is_released_two_searches_in_two_threads_overlap(tabletop):
    """Two Python threads each searching on one core finish sooner together than one after the
    other, as a ratio in this run: with the GIL held through a search they could not overlap
    (ratio 1). ctest runs this test alone (python_module_threads, RUN_SERIAL), so that both cores
    are free."""
    import threading
    import time
    scene, cup = lmk.read_cloud(tabletop), lmk.load_landmark(CUP)

    def searches():
        for _ in range(4):
            lmk.find(scene, cup, threads=1)

    searches()  # warm: the first search of a thread pays for more than the search (its heap)
    start = time.perf_counter()
    searches()
    searches()
    one_after_the_other = time.perf_counter() - start
    # Each thread warms up in the same way before the clock starts, then all three meet.
    ready = threading.Barrier(3)

    def warmed_searches():
        lmk.find(scene, cup, threads=1)
        ready.wait()
        searches()

    threads = [threading.Thread(target=warmed_searches) for _ in range(2)]
    for t in threads:
        t.start()
    ready.wait()
    start = time.perf_counter()
    for t in threads:
        t.join()
    together = time.perf_counter() - start
    # Held, the GIL would make them take as long together as apart (1.0, or more with the
    # threads' contention); free, 0.50-0.54 on two idle cores, 0.65-0.8 beside other work.
    assert together < 0.9 * one_after_the_other, (together, one_after_the_other)


def test_ctrl_c_ends_a_search_at_its_next_seed(tabletop):
    """SIGINT, sent from the first progress report, ends the search as KeyboardInterrupt before
    its seeds are done."""
    import signal
    scene, cup = lmk.read_cloud(tabletop), lmk.load_landmark(CUP)
    reports = []

    def interrupt(done, total):
        reports.append(total)
        if len(reports) == 1:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        lmk.find(scene, cup, progress=interrupt, threads=1)
    assert len(reports) < reports[0]


def without_times(value):
    """The JSON without its wall-clock times, at any depth (as `lmk eval --json` leaves them out)."""
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items()
                if not k.startswith("seconds") and k != "median_seconds_per_search"}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def test_eval_gives_lmk_eval_json_and_shares_its_cache(tmp_path):
    cache = str(tmp_path / "cache")
    got = lmk.eval(preset="paper", types=["simple/three_balls"], cache=cache)
    out = tmp_path / "eval.json"
    cli = subprocess.run([LMK, "eval", "--preset", "paper", "--types", "simple/three_balls",
                          "--cache", cache, "--json", str(out)],
                         check=True, capture_output=True, text=True)
    assert "(0 searched," in cli.stderr  # every pair came from the cache lmk.eval filled
    expected = json.loads(out.read_text())
    # The same document, the confidence's report included; Python keeps the wall time, which the
    # CLI writes with --timings only.
    assert set(got) - {"seconds"} == set(expected)
    for key in ("rows", "pairs", "confidence"):
        assert without_times(got[key]) == without_times(expected[key]), key
    assert got["rows"][0]["tp"] > 0
    with pytest.raises(ValueError, match="a dataset or a preset, not both"):
        lmk.eval(str(tmp_path), preset="paper")
    with pytest.raises(lmk.Error, match="unknown preset 'papers'"):
        lmk.eval(preset="papers", cache=cache)


def test_ablate_gives_lmk_ablate_json(tmp_path):
    cache = str(tmp_path / "cache")
    got = lmk.ablate({"metric": ["paper", "vdb"]}, preset="paper", types=["simple/three_balls"],
                     cache=cache, in_context=True)
    subprocess.run([LMK, "ablate", "--preset", "paper", "--types", "simple/three_balls",
                    "--vary", "metric=paper,vdb", "--pairs", "in-context", "--cache", cache,
                    "--out", str(tmp_path / "ablation")], check=True, capture_output=True)
    expected = json.loads((tmp_path / "ablation" / "ablation.json").read_text())
    assert [v["values"] for v in got["variants"]] == [{"metric": "paper"}, {"metric": "vdb"}]
    assert without_times(got["variants"]) == without_times(expected["variants"])
    with pytest.raises(ValueError, match="unknown"):
        lmk.ablate({"metrik": ["paper"]}, preset="paper", cache=cache)


@pytest.fixture(scope="module")
def task4(tmp_path_factory):
    """The demo's task 4 (trash against recycling): its program, landmarks and scenes."""
    out = tmp_path_factory.mktemp("demo")
    run("pbd", "demo-tasks", "--task", "4", "--save", str(out))
    return out / "task4"


def test_the_pr2_s_kinematics_on_arrays():
    robot = lmk.SimulatedPr2(torso_height=0.05)
    assert "right_arm" in robot.groups()
    joints = [0.0] * len(robot.joint_names("right_arm"))
    joints[3] = -1.0  # the elbow bent
    pose = robot.forward("right_arm", joints)
    assert pose.shape == (4, 4)
    ik = robot.inverse("right_arm", pose, seed=joints)
    assert ik["success"] and ik["position_error"] < 1e-3
    np.testing.assert_allclose(robot.forward("right_arm", ik["joints"]), pose, atol=1e-3)
    with pytest.raises(ValueError, match="no group"):
        robot.joint_names("tail")
    with pytest.raises(ValueError, match="pose: must be a 4 x 4 array"):
        robot.inverse("right_arm", np.eye(3))


def test_plan_and_run_as_lmk_pbd_and_a_refusal_with_its_kind(task4):
    program = str(task4 / "drop_in_trash.json")
    demonstration = lmk.read_cloud(str(task4 / "demonstration.pcd"))
    robot = lmk.SimulatedPr2(torso_height=0.05)
    planned = lmk.plan(program, demonstration, robot)
    cli = json.loads(run("pbd", "plan", program, "--torso", "0.05", "--json", "--scene",
                         str(task4 / "demonstration.pcd")))
    assert without_times(planned) == without_times(cli)
    assert planned["valid"] and len(planned["steps"]) == 3
    # The release is followed by the demonstrated move up: that is its retreat, none is added.
    assert [step["phase"] for step in planned["steps"]] == ["target"] * 3
    assert lmk.plan(program, demonstration, robot, approach=0)["steps"] == planned["steps"]
    with pytest.raises(ValueError, match="approach must be 0 to 0.3 m"):
        lmk.plan(program, demonstration, robot, approach=0.5)
    report = lmk.run(program, demonstration, robot)
    assert report["completed"] and report["steps_completed"] == 3
    assert robot.time > 0
    with pytest.raises(lmk.Refused) as refused:
        lmk.plan(program, lmk.read_cloud(str(task4 / "scenario4.pcd")),
                 lmk.SimulatedPr2(torso_height=0.05))
    assert refused.value.kind == "landmark-not-found"
    assert str(refused.value).startswith("landmark 'trash_opening' not found")
    assert isinstance(refused.value, lmk.Error)


def test_plan_with_collisions_checks_every_motion_as_lmk_pbd_does(task4):
    program = str(task4 / "drop_in_trash.json")
    scene = str(task4 / "demonstration.pcd")
    planned = lmk.plan(program, lmk.read_cloud(scene), lmk.SimulatedPr2(torso_height=0.05),
                       collisions=True)
    cli = json.loads(run("pbd", "plan", program, "--torso", "0.05", "--json", "--check-collisions",
                         "--scene", scene))
    assert without_times(planned) == without_times(cli)
    # Every arm's motion was checked: what it may touch (near its start and target), and how
    # near it came where anything was near (null: nothing within reach, or a motion of nothing).
    arms = [arm for step in planned["steps"] for arm in step["arms"]]
    assert arms and all(len(arm["intended_contact"]["near"]) == 2 for arm in arms)
    assert any(arm["clearance_m"] is not None and arm["clearance_m"] > 0.02 for arm in arms)
    # Where a motion goes out of the head's view, the plan says so, and warns once per motion.
    unseen = [arm for arm in arms if arm["unseen"]]
    warned = [w for w in planned["warnings"] if "passes through space no camera has seen" in w]
    assert len(warned) == len(unseen)
    # Checked by default, as the CLI; collisions=False as its --no-check-collisions.
    default = lmk.plan(program, lmk.read_cloud(scene), lmk.SimulatedPr2(torso_height=0.05))
    assert without_times(default) == without_times(planned)
    unchecked = lmk.plan(program, lmk.read_cloud(scene), lmk.SimulatedPr2(torso_height=0.05),
                         collisions=False)
    for arm in (arm for step in unchecked["steps"] for arm in step["arms"]):
        assert arm["clearance_m"] is None and not arm["intended_contact"]["near"]


def cut_by_the_image_edge(cloud, centre, margin=0.15):
    """`cloud` as a camera whose image ends before `centre` (base frame): every pixel on its side
    of the image from `margin` (in x/z, about 8 degrees) before it returns nothing."""
    to_sensor = np.linalg.inv(cloud.sensor_pose)
    c = to_sensor[:3, :3] @ centre + to_sensor[:3, 3]
    side = 1.0 if c[0] > 0 else -1.0
    points = np.array(cloud.points)  # H x W x 3, base frame
    p = points @ to_sensor[:3, :3].T + to_sensor[:3, 3]
    with np.errstate(invalid="ignore"):
        cut = side * p[..., 0] / p[..., 2] >= side * c[0] / c[2] - margin
    points[cut] = np.nan
    return lmk.Cloud(points, sensor_pose=cloud.sensor_pose)


def test_plan_looks_again_through_a_python_head(task4):
    program = str(task4 / "drop_in_trash.json")
    demonstration = lmk.read_cloud(str(task4 / "demonstration.pcd"))
    planned = lmk.plan(program, demonstration, lmk.SimulatedPr2(torso_height=0.05), collisions=False)
    trash = next(l for l in planned["landmarks"] if l["name"] == "trash_opening")
    cut = cut_by_the_image_edge(demonstration, np.array(trash["position"]))
    with pytest.raises(lmk.Refused, match="trash_opening' not found"):
        lmk.plan(program, cut, lmk.SimulatedPr2(torso_height=0.05), collisions=False)

    # The head turns and sees the whole scene: the new frame is fused with the cut one.
    targets = []

    def look(target):
        targets.append(target)
        return demonstration

    looked = lmk.plan(program, cut, lmk.SimulatedPr2(torso_height=0.05), collisions=False, look=look)
    assert looked["valid"] and len(targets) == 1 and targets[0].shape == (3,)
    assert len(looked["looks"]) == 1 and "missing 'trash_opening'" in looked["looks"][0]["why"]
    np.testing.assert_allclose(looked["looks"][0]["target"], targets[0])

    # A head that never sees it: refused after look_again looks, naming them.
    targets.clear()
    with pytest.raises(lmk.Refused, match="after 1 more look") as refused:
        lmk.plan(program, cut, lmk.SimulatedPr2(torso_height=0.05), collisions=False, look=lambda t: cut,
                 look_again=1)
    assert refused.value.kind == "landmark-not-found"
    # What the head raises is raised, not turned into a refusal; bad arguments are ValueErrors.
    def broken(target):
        raise KeyError("the head's driver is gone")
    with pytest.raises(KeyError, match="driver is gone"):
        lmk.plan(program, cut, lmk.SimulatedPr2(torso_height=0.05), collisions=False, look=broken)
    with pytest.raises(TypeError, match="must return an lmk.Cloud"):
        lmk.plan(program, cut, lmk.SimulatedPr2(torso_height=0.05), collisions=False, look=lambda t: None)
    with pytest.raises(ValueError, match="look_again needs look"):
        lmk.plan(program, cut, lmk.SimulatedPr2(torso_height=0.05), collisions=False, look_again=2)
    with pytest.raises(ValueError, match="look_again must be 0 to 8"):
        lmk.plan(program, cut, lmk.SimulatedPr2(torso_height=0.05), collisions=False, look=look, look_again=9)
    # Looks where checked motions go unseen (issue #60) need the head as well.
    with pytest.raises(ValueError, match="unseen_looks needs look"):
        lmk.plan(program, cut, lmk.SimulatedPr2(torso_height=0.05), collisions=True,
                 unseen_looks=1)
    with pytest.raises(ValueError, match="unseen_looks must be 0 to 8"):
        lmk.plan(program, cut, lmk.SimulatedPr2(torso_height=0.05), look=look, unseen_looks=-1)


def test_the_stub_names_everything_the_module_has():
    import ast
    stub = os.path.join(os.path.dirname(lmk.__file__), "__init__.pyi")
    tree = ast.parse(open(stub).read())
    named = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    named |= {t.id for n in tree.body if isinstance(n, (ast.Assign, ast.AnnAssign))
              for t in (n.targets if isinstance(n, ast.Assign) else [n.target])}
    public = {name for name in dir(lmk) if not name.startswith("_") and name != "lmk"}
    assert public - named == set()
    for name in public:  # and each has its docstring
        assert getattr(lmk, name).__doc__, name


EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "examples")


def test_find_in_frame_example_finds_the_cup(tabletop):
    box = lmk.load_landmark(CUP).box
    centre, size = box["pose"][:3, 3], box["size"]
    out = subprocess.run(["/usr/bin/python3", os.path.join(EXAMPLES, "find_in_frame.py"), tabletop,
                          *map(str, centre), *map(str, size), "cup"],
                         check=True, capture_output=True, text=True, env=os.environ).stdout
    assert "captured 'cup'" in out and "1: at" in out


def test_ablate_metrics_example_draws_a_plot_that_is_not_blank(tmp_path):
    png = tmp_path / "metrics.png"
    subprocess.run(["/usr/bin/python3", os.path.join(EXAMPLES, "ablate_metrics.py"), str(png),
                    "--types", "simple/three_balls", "--cache", str(tmp_path / "cache")],
                   check=True, capture_output=True, text=True, env=os.environ)
    import matplotlib.image
    pixels = matplotlib.image.imread(str(png))
    assert pixels.shape[0] > 100 and pixels.std() > 0.05  # lines and text, not one colour


def test_tracker_follows_the_cup_as_lmk_track_does(tabletop, tmp_path):
    """lmk.Tracker (issue #48): found, then followed, in the frames `lmk track` follows it in."""
    scene, cup = lmk.read_cloud(tabletop), lmk.load_landmark(CUP)
    tracker = lmk.Tracker([cup], max_tilt=60)
    states = [tracker.update(scene)[0] for _ in range(3)]
    assert [s["state"] for s in states] == ["found", "tracking", "tracking"]
    cli = [json.loads(line) for line in
           run("track", tabletop, tabletop, tabletop, CUP, "--json", "-").splitlines()]
    assert [c["state"] for c in cli] == [s["state"] for s in states]
    for got, line in zip(states, cli):
        assert got["pose"].shape == (4, 4)
        np.testing.assert_allclose(got["box"]["pose"][:3, 3], line["position"], atol=1e-9)
        assert got["error"] == pytest.approx(line["error"], abs=1e-12)
        # One writer: the fields of the line `lmk track --json` writes, but the frame's number and
        # file (and its seconds, which the CLI writes only with --timings); and lmk.find's pose
        # and box besides.
        assert set(got) - {"pose", "box", "seconds"} == set(line) - {"frame", "file", "seconds"}
        assert got["landmark"] == line["landmark"]
    with pytest.raises(ValueError, match="max_tilt"):
        lmk.Tracker([cup], max_tilt=500)
    with pytest.raises(ValueError, match="margin"):
        lmk.Tracker([cup], follow_margin=5.0)
    with pytest.raises(ValueError, match="follow_threshold_factor"):
        lmk.Tracker([cup], follow_threshold_factor=0.5)
    with pytest.raises(ValueError, match="camera_motion"):
        lmk.Tracker([cup], camera_motion="sideways")
    # Named modes as the CLI's: the same states whichever, on one still frame repeated.
    for motion in ("none", "estimated"):
        again = lmk.Tracker([cup], max_tilt=60, camera_motion=motion)
        assert [again.update(scene)[0]["state"] for _ in range(2)] == ["found", "tracking"]
