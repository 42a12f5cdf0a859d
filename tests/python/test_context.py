# test_context.py: the EGL device the module renders on (lucent.devices, lucent.Context) and releasing its
# context (close, a `with` block, lucent.release), after which a render creates a fresh one.
import numpy as np
import pytest

import lucent

ARGS = dict(method="per-pixel", params={"N": 4, "light_map_size": 64}, width=16, height=12, frames=1)


def test_devices_and_a_bad_index():
    devices = lucent.devices()
    assert devices and all(isinstance(d, str) and d for d in devices)
    count = len(devices)
    with pytest.raises(ValueError, match=rf"^device {count} does not exist; there (is|are) {count} EGL device"):
        lucent.Context(device=count)
    with pytest.raises(ValueError, match=r"^device -1 does not exist"):
        lucent.Context(device=-1)


def test_renders_on_a_chosen_device_and_after_release():
    scene = lucent.load_scene()
    first = lucent.render(scene, **ARGS)
    context = lucent.Context(device=0)
    assert context.device == 0 and not context.closed and "OpenGL" in context.description
    np.testing.assert_array_equal(lucent.render(scene, **ARGS), first)
    context.close()
    assert context.closed
    np.testing.assert_array_equal(lucent.render(scene, **ARGS), first)  # a fresh context, the same device
    lucent.release()
    lucent.release()  # nothing to release: no error
    with lucent.Context() as default:
        assert default.device is None and not default.closed
        np.testing.assert_array_equal(lucent.render(scene, **ARGS), first)
    assert default.closed
    np.testing.assert_array_equal(lucent.render(scene, **ARGS), first)


def test_a_new_context_replaces_the_previous_one():
    old = lucent.Context()
    new = lucent.Context(device=0)
    assert old.closed and not new.closed
    old.close()  # no longer the module's: leaves the new one open
    assert not new.closed
    new.close()
