# test_compare.py: lucent.compare() against closed forms and `lucent compare --json` on the same files.
import json
import math

import numpy as np
import pytest

import lucent
from conftest import run_cli


def images():
    rng = np.random.default_rng(7)
    b = rng.uniform(0.1, 2.0, size=(6, 9, 3)).astype(np.float32)
    a = (b + rng.normal(0.0, 0.05, size=b.shape)).astype(np.float32)
    se = np.full(b.shape, 0.01, dtype=np.float32)
    return a, b, se


def test_constant_offset_closed_form():
    b = np.full((4, 5, 3), 0.5, dtype=np.float32)
    a = b + np.float32(0.25)
    linear = lucent.compare(a, b)["linear"]
    assert linear["rmse"] == pytest.approx([0.25] * 3, rel=1e-6)
    assert linear["rmse_rgb"] == pytest.approx(0.25 * math.sqrt(3.0), rel=1e-6)
    assert linear["mean_error"] == pytest.approx(0.25, rel=1e-6)
    assert linear["relative_mse"] == pytest.approx(0.25**2 / (0.5**2 + 1e-2), rel=1e-6)


def test_equals_the_cli(out_dir):
    a, b, se = images()
    lucent.write_exr(str(out_dir / "a.exr"), a)
    lucent.write_exr(str(out_dir / "b.exr"), b)
    lucent.write_exr(str(out_dir / "b.stderr.exr"), se)
    cli = json.loads(run_cli("compare", "--json", "--exposure", "0.5", out_dir / "a.exr", out_dir / "b.exr").stdout)
    py = lucent.compare(a, b, standard_error=se, exposure=0.5)
    assert py == {"linear": cli["linear"], "display": cli["display"]}
    assert py["linear"]["reference_noise_rms"] == pytest.approx(0.01, rel=1e-6)


def test_read_exr_round_trip(out_dir):
    a, _, _ = images()
    lucent.write_exr(str(out_dir / "a.exr"), a)
    assert np.array_equal(lucent.read_exr(str(out_dir / "a.exr")), a)


def test_image_writes_refuse_nul_bytes_and_misnamed_formats(out_dir):
    """A NUL byte would cut the name handed to the system (EXR bytes landing in x.png); a name must say the format."""
    a, _, _ = images()
    png = out_dir / "x.png"
    with pytest.raises(lucent.Error, match=r"NUL byte"):
        lucent.write_exr(str(png) + "\0.exr", a)
    with pytest.raises(lucent.Error, match=r"'\.png' is not a format this command writes; use \.exr"):
        lucent.write_exr(str(png), a)
    with pytest.raises(lucent.Error, match=r"'\.exr' is not a format this command writes; use \.png"):
        lucent.write_png(str(out_dir / "x.exr"), a)
    assert not png.exists() and not (out_dir / "x.exr").exists()


def test_size_mismatch_message():
    with pytest.raises(lucent.Error, match=r"^a is 3x2 but b is 2x2; compare needs images of one size$"):
        lucent.compare(np.zeros((2, 3, 3)), np.zeros((2, 2, 3)))
    with pytest.raises(lucent.Error, match=r"^a: expected an array of shape \(height, width, 3\) or \(height, width, 4\), got \(2, 3\)$"):
        lucent.compare(np.zeros((2, 3)), np.zeros((2, 2, 3)))


def test_identical_and_black_references_have_no_finite_psnr():
    b = np.full((4, 5, 3), 0.5, dtype=np.float32)
    linear = lucent.compare(b, b)["linear"]
    assert linear["psnr_db"] is None and linear["psnr"] == "inf dB"
    assert linear["rmse"] == [0.0, 0.0, 0.0]
    black = np.zeros_like(b)
    linear = lucent.compare(b, black)["linear"]
    assert linear["psnr_db"] is None and linear["psnr"].startswith("undefined")
    a = b + np.float32(0.25)
    linear = lucent.compare(a, b)["linear"]
    assert linear["psnr_db"] == pytest.approx(float(linear["psnr"].split()[0]), abs=0.01)
