# test_warnings.py: lucent's warnings arrive through Python's warnings module as lucent.LucentWarning, also those
# raised on the render's own threads, and no longer go to the process's stderr.
import warnings

import pytest

import lucent

SMALL_RENDER = dict(method="radiosity-maps", params={"K": 4, "N": 8, "map_size": 32, "light_map_size": 64, "vpls": 0},
                    width=16, height=12, frames=1)


def test_a_scene_without_lights_warns_in_python(capfd):
    assert issubclass(lucent.LucentWarning, UserWarning)
    scene = lucent.load_scene()
    with pytest.warns(lucent.LucentWarning, match="no light") as record:
        scene.set("lights", [])
    assert len(record) == 1 and record[0].filename == __file__  # points at the caller's line
    assert "warning" not in capfd.readouterr().err


def test_a_warning_on_the_render_thread_reaches_the_caller(capfd):
    scene = lucent.load_scene().set("objects.torus.material", "Strawberry Shampoo")
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        lucent.render(scene, **SMALL_RENDER)
    messages = [str(w.message) for w in record if w.category is lucent.LucentWarning]
    assert any(m.startswith("torus: reduced albedo") for m in messages), messages
    assert "warning" not in capfd.readouterr().err


def test_warnings_as_errors_keep_the_scene():
    scene = lucent.load_scene()
    with warnings.catch_warnings():
        warnings.simplefilter("error", lucent.LucentWarning)
        with pytest.raises(lucent.LucentWarning, match="no light"):
            scene.set("lights", [])
    assert len(scene.lights) == 1 and scene.overrides == []
