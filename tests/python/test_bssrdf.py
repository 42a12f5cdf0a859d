# test_bssrdf.py: lucent.bssrdf() against `lucent bssrdf --json` and the standard dipole's closed form.
import json
import math

import pytest

import lucent
from conftest import run_cli


@pytest.mark.parametrize("model", ["directional", "standard", "photon-beam", "better-dipole"])
def test_bssrdf_equals_the_cli(model):
    cli = json.loads(run_cli("bssrdf", "--json", "--material", "Skin1", "--model", model, "--xo", "0.7,0.2,0",
                             "--wi", "0.3,0,1").stdout)
    py = lucent.bssrdf("Skin1", model=model, xo=(0.7, 0.2, 0.0), wi=(0.3, 0.0, 1.0))
    assert list(py["S_d"]) == cli["S_d"]  # the same float32 code: bit for bit
    assert py["T12"] == cli["T12"]
    assert (py["model"], py["material"], py["eta"]) == (cli["model"], cli["material"], cli["eta"])


def test_standard_dipole_closed_form():
    # Index-matched (eta = 1: A = 1, no exit normalisation): S_d = R_d(r) / pi (Jensen et al. 2001, eq. 4-6).
    sigma_a, sigma_s_prime, r = (0.02, 0.05, 0.1), (1.1, 2.0, 0.7), 0.8
    py = lucent.bssrdf({"sigma_a": sigma_a, "sigma_s_prime": sigma_s_prime, "eta": 1.0}, model="standard",
                       xo=(r, 0.0, 0.0))
    for band in range(3):
        st = sigma_a[band] + sigma_s_prime[band]
        alpha, D = sigma_s_prime[band] / st, 1.0 / (3.0 * st)
        tr = math.sqrt(3.0 * sigma_a[band] * st)
        z_r = 1.0 / st
        z_v = z_r + 4.0 * D
        term = lambda z: z * (1.0 + tr * math.hypot(r, z)) * math.exp(-tr * math.hypot(r, z)) / math.hypot(r, z) ** 3
        Rd = alpha / (4.0 * math.pi) * (term(z_r) + term(z_v))
        assert py["S_d"][band] == pytest.approx(Rd / math.pi, rel=2e-5)


def test_total_equals_the_cli():
    cli = json.loads(run_cli("bssrdf", "--total", "--json", "--material", "Marble", "--model", "standard",
                             "--incidence-deg", "30").stdout)
    py = lucent.bssrdf_total("Marble", model="standard", incidence_deg=30.0)
    assert list(py["total"]) == cli["total"] and list(py["radiosity"]) == cli["radiosity"]
    assert py["exit_transmittance"] == cli["exit_transmittance"]


def test_total_closed_form():
    # Index-matched, the standard dipole's radiosity (pi x integral of S_d) is its closed-form total diffuse
    # reflectance R_total = a'/2 (1 + exp(-4/3 A sqrt(3 (1 - a')))) exp(-sqrt(3 (1 - a'))) with A = 1
    # (Jensen et al. 2001); the integration is accurate to about 1e-4.
    sigma_a, sigma_s_prime = (0.01, 0.1, 0.5), (1.0, 1.5, 0.8)
    py = lucent.bssrdf_total({"sigma_a": sigma_a, "sigma_s_prime": sigma_s_prime, "eta": 1.0}, model="standard")
    for band in range(3):
        alpha = sigma_s_prime[band] / (sigma_a[band] + sigma_s_prime[band])
        s = math.sqrt(3.0 * (1.0 - alpha))
        R_total = 0.5 * alpha * (1.0 + math.exp(-4.0 / 3.0 * s)) * math.exp(-s)
        assert py["radiosity"][band] == pytest.approx(R_total, rel=1e-3)


def test_bad_material_is_the_cli_message():
    with pytest.raises(lucent.Error) as error:
        lucent.bssrdf({"sigma_a": 0.0, "sigma_s": 1.0})
    cli = run_cli("bssrdf", "--sigma-a", "0", "--sigma-s", "1", check=False)
    assert cli.returncode == 1
    assert cli.stderr == f"lucent: {error.value}\n"
