# test_reference.py: lucent.reference() gives the mean and standard error `lucent reference` writes.
import numpy as np
import pytest

import lucent
from conftest import SCENES, run_cli


@pytest.mark.parametrize("integrator", ["volpath", "bssrdf"])
def test_reference_equals_the_cli(out_dir, integrator):
    scene = lucent.load_scene(str(SCENES / "default.json"))
    mean, se = lucent.reference(scene, integrator=integrator, spp=2, seed=3, width=24, height=16)
    exr = out_dir / "ref.exr"
    run_cli("reference", SCENES / "default.json", "-q", "--integrator", integrator, "--spp", 2, "--seed", 3,
            "--set", "render.width=24", "--set", "render.height=16", "-o", exr)
    assert mean.shape == (16, 24, 3) and se.shape == (16, 24, 3)
    assert mean.max() > 0.01 and se.max() > 0.0
    # Deterministic from (seed, pixel, sample): the same numbers whatever the thread count.
    np.testing.assert_allclose(mean, lucent.read_exr(str(exr)), rtol=1e-6, atol=1e-7)
    np.testing.assert_allclose(se, lucent.read_exr(str(out_dir / "ref.stderr.exr")), rtol=1e-6, atol=1e-7)


def test_bad_integrator_message():
    with pytest.raises(lucent.Error, match=r"^integrator: 'photon' is not one of volpath, bssrdf$"):
        lucent.reference(lucent.load_scene(), integrator="photon")
