"""Bad input from Python raises a clear exception and never crashes the interpreter."""

import os
import signal
import subprocess
import sys
import textwrap
import threading

import pytest

import brume
from conftest import ROOT, SCENE, SMALL


def test_an_unknown_key_names_file_line_column_and_key(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(SCENE.read_text().replace("[camera]\n", "[camera]\nwidht = 3\n"))
    with pytest.raises(brume.SceneError) as e:
        brume.load(bad)
    assert str(e.value).startswith(f"{bad}:14:1: key `camera.widht`: "), str(e.value)


def test_a_wrong_type_in_the_file_names_its_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(SCENE.read_text().replace("width = 256", 'width = "wide"'))
    with pytest.raises(brume.SceneError, match=r"bad\.toml:15:9: key `camera\.width`"):
        brume.load(bad)


def test_toml_text_errors_name_the_string():
    with pytest.raises(brume.SceneError, match=r"^<string>:1:1: key `cmaera`"):
        brume.load("cmaera = 1\n")


def test_a_set_value_of_the_wrong_type_is_a_scene_error_naming_the_set():
    with pytest.raises(brume.SceneError, match=r"--set camera\.width=\"wide\""):
        brume.load(SCENE, set={"camera.width": "wide"})
    with pytest.raises(brume.SceneError, match="media.fgo"):
        brume.load(SCENE, set={"media.fgo.g": 0.5})


def test_a_set_value_python_cannot_say_in_toml_is_a_type_error():
    with pytest.raises(TypeError, match="camera.width: a object is not a scene value"):
        brume.load(SCENE, set={"camera.width": object()})
    with pytest.raises(TypeError, match="keys are dotted paths"):
        brume.load(SCENE, set={3: 1})
    with pytest.raises(TypeError):
        brume.load(SCENE, set=[("camera.width", 3)])
    with pytest.raises(TypeError):
        brume.load(42)


def test_a_missing_file_is_a_scene_error():
    with pytest.raises(brume.SceneError, match="cannot read scene file"):
        brume.load("no/such/scene.toml")


@pytest.mark.parametrize("kwargs, message", [
    ({"passes": -1}, "passes=-1"),
    ({"passes": 0}, "passes=0"),
    ({"time": -2.0}, "time=-2: expected a positive number of seconds"),
    ({"time": float("nan")}, "time=NaN"),
    ({"passes": 2, "time": 1.0}, "one of passes, time and pass_range"),
    ({"pass_range": (3, 3)}, r"pass_range \(3, 3\)"),
    ({"pass_range": (-1, 2)}, r"pass_range \(-1, 2\)"),
    ({"seed": -5}, "seed=-5"),
    ({"threads": 100000}, "threads=100000"),
])
def test_bad_render_arguments_are_value_errors(kwargs, message):
    scene = brume.load(SCENE, set=SMALL)
    with pytest.raises(ValueError, match=message):
        scene.render(progress=False, **kwargs)


def test_wrong_argument_types_are_type_errors():
    scene = brume.load(SCENE, set=SMALL)
    with pytest.raises(TypeError):
        scene.render(passes="many", progress=False)
    with pytest.raises(TypeError):
        scene.render(passes=1, progress="yes")


def test_rendering_from_two_threads_at_once_is_refused():
    scene = brume.load(SCENE, set={**SMALL, "integrator.forward_rays": 200000})
    started, errors, results = threading.Event(), [], []

    def slow(done, total, passes):
        started.set()

    def first():
        results.append(scene.render(passes=3, seed=1, progress=slow))

    t = threading.Thread(target=first)
    t.start()
    assert started.wait(120)
    try:
        scene.render(passes=1, progress=False)
    except brume.RenderError as e:
        errors.append(str(e))
    t.join()
    assert errors and "another render is running in this process" in errors[0]
    assert results and results[0].passes == 3
    # The slot is free again.
    assert scene.render(passes=1, seed=1, progress=False).passes == 1


def test_merging_films_of_other_renders_is_refused(tmp_path):
    scene = brume.load(SCENE, set=SMALL)
    a = scene.render(pass_range=(0, 1), seed=1, progress=False)
    b = scene.render(pass_range=(1, 2), seed=2, progress=False)
    with pytest.raises(brume.FilmError, match="seed 2 in films\\[1\\], 1 in films\\[0\\]"):
        brume.merge([a, b])
    c = scene.render(pass_range=(2, 3), seed=1, progress=False)
    with pytest.raises(brume.FilmError, match="cannot merge"):
        brume.merge([a, c])
    with pytest.raises(TypeError):
        brume.merge([a, 3])
    (tmp_path / "junk.brume").write_bytes(b"not a film")
    with pytest.raises(brume.FilmError):
        brume.read_film(tmp_path / "junk.brume")
    with pytest.raises(ValueError, match="unsupported output extension"):
        a.save(tmp_path / "x.jpg")


def test_ctrl_c_raises_keyboard_interrupt_and_returns_nothing():
    # In a child interpreter: SIGINT to itself one second into a long render. A shell runs a
    # background job (`cmd &`) with SIGINT ignored, its children inherit that, and Python then
    # leaves it ignored: the child restores the handler that an interactive Python has, so
    # that the test means the same however the suite was started.
    code = textwrap.dedent(f"""
        import os, signal, sys, threading, time
        signal.signal(signal.SIGINT, signal.default_int_handler)
        import brume
        scene = brume.load({str(SCENE)!r}, set={{"camera.width": 24, "camera.height": 12}})
        threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        result = None
        t0 = time.monotonic()
        try:
            result = scene.render(passes=100000, progress=False)
        except KeyboardInterrupt:
            print("interrupted after", round(time.monotonic() - t0, 1), "s; result", result)
            sys.exit(3)
        print("not interrupted")
    """)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                       cwd=ROOT)
    assert r.returncode == 3, r.stdout + r.stderr
    assert "result None" in r.stdout


def test_a_missing_texture_is_a_scene_error_from_render(tmp_path):
    # Whether loading or building finds it, the error is the scene's, naming the file.
    text = (ROOT / "scenes" / "fog-cube.toml").read_text()
    with pytest.raises(brume.SceneError, match="no-such.png"):
        scene = brume.load(text.replace("textures/brume-pattern.png", "no-such.png"),
                           set={"camera.width": 8, "camera.height": 8})
        scene.render(passes=1, progress=False)


def test_a_render_larger_than_memory_is_refused_unless_forced():
    # 32768 x 4096 pixels of 64 bins: the film alone is over 24 GiB, refused before any
    # allocation, as the CLI refuses it without --force.
    scene = brume.load(SCENE, set={"camera.width": 32768, "camera.height": 4096, "film.bins": 64})
    with pytest.raises(brume.RenderError, match="force=True"):
        scene.render(passes=1, progress=False)
