# test_tonemap.py: lucent.tonemap gives the pixels `lucent render` writes to its PNG from the radiance it writes
# to its EXR (the same tone curve, exposure and operator), and the curve's values at known points.
import struct
import zlib

import numpy as np
import pytest

import lucent
from conftest import run_cli


def read_png(path):
    """8-bit RGB or RGBA PNG -> uint8 (height, width, channels), without an imaging library."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, chunks, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            chunks += body
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and colour in (2, 6) and interlace == 0
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(chunks)
    stride = width * channels
    out = np.zeros((height, stride), dtype=np.int32)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        up = out[y - 1] if y > 0 else np.zeros(stride, np.int32)
        row = np.zeros(stride, np.int32)
        for x in range(stride):
            left = row[x - channels] if x >= channels else 0
            upleft = up[x - channels] if x >= channels else 0
            if kind == 0: predictor = 0
            elif kind == 1: predictor = left
            elif kind == 2: predictor = up[x]
            elif kind == 3: predictor = (left + up[x]) // 2
            else:
                p = left + up[x] - upleft
                pa, pb, pc = abs(p - left), abs(p - up[x]), abs(p - upleft)
                predictor = left if pa <= pb and pa <= pc else up[x] if pb <= pc else upleft
            row[x] = (line[x] + predictor) & 255
        out[y] = row
    return out.reshape(height, width, channels).astype(np.uint8)


@pytest.mark.parametrize("operator, exposure", [("aces", 0.0), ("reinhard", 1.0), ("linear", -0.5)])
def test_tonemap_equals_the_render_png(out_dir, operator, exposure):
    png, exr = out_dir / "r.png", out_dir / "r.exr"
    run_cli("render", "-q", "--frames", 1, "-o", png, "--exr", exr, "--set", "render.width=24", "--set",
            "render.height=16", "--set", f"render.tonemap={operator}", "--set", f"render.exposure={exposure}",
            "--set", 'method={"name": "per-pixel", "N": 4, "light_map_size": 64}')
    expected = read_png(png)[:, :, :3]
    shown = lucent.tonemap(lucent.read_exr(str(exr)), exposure=exposure, operator=operator)
    assert shown.dtype == np.uint8 and shown.shape == expected.shape
    assert expected.max() > 20  # lit
    # The GPU pass and the CPU evaluate the same code in float: at most one level apart where rounding differs.
    assert np.abs(shown.astype(int) - expected.astype(int)).max() <= 1


def srgb(x):
    x = np.clip(x, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)


def test_curves_at_known_points():
    radiance = np.array([[[0.0, 0.18, 1.0], [4.0, 0.5, 2.0]]], dtype=np.float32)
    x = radiance * 2.0  # exposure 1 stop
    aces = np.clip(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)  # Narkowicz 2015
    expected = {"aces": srgb(aces), "reinhard": srgb(x / (1 + x)), "linear": srgb(x)}
    for operator, values in expected.items():
        shown = lucent.tonemap(radiance, exposure=1.0, operator=operator, dtype="float32")
        assert shown.dtype == np.float32
        np.testing.assert_allclose(shown, values, atol=2e-6)
        np.testing.assert_array_equal(lucent.tonemap(radiance, exposure=1.0, operator=operator),
                                      np.round(values * 255).astype(np.uint8))
    with pytest.raises(ValueError, match="operator: 'filmic' is not one of aces, reinhard, linear"):
        lucent.tonemap(radiance, operator="filmic")


def test_nan_has_no_display_value():
    """A NaN pixel is named, not shown as 0 (uint8) or passed on as NaN (float32)."""
    radiance = np.full((2, 3, 3), 0.5, dtype=np.float32)
    radiance[1, 2, 1] = np.nan
    for dtype in ("uint8", "float32"):
        with pytest.raises(lucent.Error, match=r"^image has a NaN at pixel \(2, 1\), green: it has no colour to display$"):
            lucent.tonemap(radiance, dtype=dtype)
