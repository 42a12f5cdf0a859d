# test_catalog.py: lucent.methods() and lucent.materials() list what `lucent methods --json` and
# `lucent materials` print.
import json

import lucent
from conftest import run_cli


def test_methods_equal_the_cli_json():
    cli = json.loads(run_cli("methods", "--json").stdout)
    assert lucent.methods() == cli
    assert [m["name"] for m in cli][0] == next(m["name"] for m in cli if m["default"])


def test_methods_carry_their_parameters():
    by_name = {m["name"]: m for m in lucent.methods()}
    K = next(p for p in by_name["radiosity-maps"]["params"] if p["name"] == "K")
    assert K["type"] == "int" and K["update"] in ("live", "rebuild")


def test_materials_equal_the_cli_table():
    lines = run_cli("materials").stdout.splitlines()[1:]
    presets = lucent.materials()
    assert len(lines) == len(presets)
    v3 = lambda v: " ".join(f"{x:.4g}" for x in v)
    for line, p in zip(lines, presets):
        assert line.startswith(p["name"] + " ")
        assert f" {v3(p['sigma_a'])} " in line
        assert f" {v3(p['sigma_s'])}{' (reduced)' if p['reduced'] else ''} " in line
        assert ("[not usable by the diffusion models" in line) == (not p["usable"])
