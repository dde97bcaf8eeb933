"""Bearing elements for ROSS from bearing-set results (issue 25 §6, racetrace.rotordynamics,
docs/rotordynamics.md): the coefficients, the TOML files `racetrace export --ross` writes, and,
with ROSS installed (the extra racetrace[ross]), the elements of a DB pair in a ROSS rotor whose
natural frequencies rise with the pair's preload."""

from __future__ import annotations

import subprocess
import sys
import tomllib

import numpy as np
import pytest

import solver
from racetrace.rotordynamics import RossExportError, ross_bearing_arguments

PRELOADS = ("light", "medium", "heavy")
SPEEDS_RPM = (0.0, 12000.0)


def _ross():
    """ROSS, or a skip: it is an optional extra (and ROSS 2.3, the last for Python 3.11, fails
    at import with plotly 7: docs/rotordynamics.md)."""
    try:
        import ross
    except Exception as error:  # noqa: BLE001 - any failure to import means: not usable here
        pytest.skip(f"ROSS cannot be imported here: {type(error).__name__}")
    return ross


@pytest.fixture(scope="module")
def pair_results():
    """{preload class: [set result at each speed of SPEEDS_RPM]} of the shipped DB pairs."""
    out = {}
    for name in PRELOADS:
        case = solver.catalogue().get(f"spindle-pair-db-{name}-preload").load()
        out[name] = [
            solver.solve(case.with_values({"operating.inner_ring_speed_rpm": s}))
            for s in SPEEDS_RPM
        ]
    return out


def test_the_coefficients_are_the_bearings_radial_stiffness_in_rosss_axes(pair_results):
    results = pair_results["light"]
    one = ross_bearing_arguments(results[1], [3, 4])
    k = results[1]["bearing_stiffness"]
    for b, element in enumerate(one):
        kb = k.isel(bearing=b)
        assert element["n"] == 3 + b and element["tag"] == f"bearing {b + 1}"
        # ROSS (x, y, z) = racetrace (y, z, x): z is ROSS's rotor axis
        assert element["kxx"] == float(kb.sel(dof="y", dof_="y"))
        assert element["kyy"] == float(kb.sel(dof="z", dof_="z"))
        assert element["kxy"] == float(kb.sel(dof="y", dof_="z"))
        assert element["kyx"] == float(kb.sel(dof="z", dof_="y"))
        assert element["kzz"] == float(kb.sel(dof="x", dof_="x"))
        assert element["kxx"] > 1e7  # N/m: a preloaded spindle bearing
        assert element["cxx"] == element["czz"] == 0.0  # the quasi-static model has no damping
        assert "frequency" not in element  # one result: constant coefficients
    # over speeds (given in any order): lists over ascending speeds in rad/s
    over = ross_bearing_arguments(results[::-1], [3, 4])
    assert over[0]["frequency"] == pytest.approx([s * np.pi / 30 for s in SPEEDS_RPM])
    assert over[0]["kxx"][1] == one[0]["kxx"]
    assert over[0]["kxx"][0] != over[0]["kxx"][1]  # the stiffness changes with speed


@pytest.mark.parametrize(
    ("nodes", "twice", "words"),
    [
        ([3], False, "give one ROSS shaft node (an integer >= 0) per bearing"),
        ([3, -1], False, "give one ROSS shaft node"),
        ([3, 4], True, "two results have the same inner-ring speed"),
    ],
)
def test_bad_nodes_or_results_are_named(pair_results, nodes, twice, words):
    results = pair_results["light"][:1] * (2 if twice else 1)
    with pytest.raises(RossExportError) as info:
        ross_bearing_arguments(results, nodes)
    assert words in str(info.value)


def test_a_single_bearing_result_is_refused():
    ds = solver.solve(solver.catalogue().get("spindle-axial-preload").load())
    with pytest.raises(RossExportError) as info:
        ross_bearing_arguments(ds, [0])
    assert "not a bearing-set result" in str(info.value)


def test_a_dynamic_set_run_is_refused_naming_the_quasistatic_solve():
    case = solver.catalogue().get("spindle-pair-db-light-preload").load()
    run = solver.simulate(case.with_values({"simulation.shaft_revolutions": 0.05}))
    assert run.sizes["bearing"] == 2
    with pytest.raises(RossExportError) as info:
        ross_bearing_arguments(run, [3, 4], source="run.nc")
    message = str(info.value)
    assert "run.nc is a dynamic run of a bearing set" in message
    assert "racetrace solve CASE --output FILE.nc" in message


def racetrace(*args):
    return subprocess.run(
        [sys.executable, "-m", "racetrace", *args], capture_output=True, text=True, timeout=300
    )


@pytest.fixture(scope="module")
def saved(pair_results, tmp_path_factory):
    folder = tmp_path_factory.mktemp("sets")
    paths = []
    for ds, speed in zip(pair_results["light"], SPEEDS_RPM, strict=True):
        path = folder / f"light-{speed:.0f}.nc"
        solver.save_dataset(ds, path)
        paths.append(str(path))
    return paths


def test_export_ross_writes_one_element_file_per_bearing(pair_results, saved, tmp_path):
    out = racetrace("export", *saved, "--ross", str(tmp_path / "ross"), "--nodes", "3,4")
    assert out.returncode == 0, out.stderr
    files = sorted((tmp_path / "ross").glob("*.toml"))
    assert [f.name for f in files] == ["bearing-1.toml", "bearing-2.toml"]
    expected = ross_bearing_arguments(pair_results["light"], [3, 4])
    for path, arguments in zip(files, expected, strict=True):
        data = tomllib.loads(path.read_text("utf-8"))
        assert data == {f"BearingElement_{arguments['tag']}": arguments}
        assert f"wrote {path}" in out.stderr


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        ([], "--ross needs --nodes N1,N2"),
        (["--nodes", "3,x"], "give integers separated by commas"),
        (["--nodes", "3"], "give one ROSS shaft node"),
    ],
)
def test_export_ross_refuses_bad_input_with_exit_2(saved, tmp_path, extra, words):
    out = racetrace("export", saved[0], "--ross", str(tmp_path / "ross"), *extra)
    assert out.returncode == 2
    assert "Traceback" not in out.stderr
    assert words in out.stderr
    assert not list(tmp_path.glob("ross/*.toml"))


def _rotor(ross, bearings):
    """A spindle-like rotor: a 40 mm steel shaft, the pair's bearings at nodes 1 and 2 (15 mm
    apart, the pair's spacing), a tool-side disk at the nose (node 0) and a drive disk at the
    rear (node 5)."""
    steel = ross.Material(name="steel", rho=7810.0, E=211e9, G_s=81.2e9)
    lengths = (0.06, 0.015, 0.1, 0.1, 0.1)
    shaft = [
        ross.ShaftElement(L=length, idl=0.0, odl=0.04, material=steel, n=i)
        for i, length in enumerate(lengths)
    ]
    disks = [
        ross.DiskElement.from_geometry(n=0, material=steel, width=0.03, i_d=0.04, o_d=0.12),
        ross.DiskElement.from_geometry(n=5, material=steel, width=0.03, i_d=0.04, o_d=0.10),
    ]
    return ross.Rotor(shaft, disks, bearings)


def test_pair_elements_run_in_a_ross_rotor_and_stiffen_it_with_preload(
    pair_results, saved, tmp_path
):
    ross = _ross()
    from racetrace.rotordynamics import ross_elements

    # the files racetrace writes are what ROSS itself loads
    out = racetrace("export", *saved, "--ross", str(tmp_path), "--nodes", "1,2")
    assert out.returncode == 0, out.stderr
    built = ross_elements(pair_results["light"], [1, 2])
    loaded = [ross.BearingElement.load(tmp_path / f"bearing-{i}.toml") for i in (1, 2)]
    assert loaded == built
    speed = SPEEDS_RPM[1] * np.pi / 30.0
    frequencies = {}
    for name in PRELOADS:
        rotor = _rotor(ross, ross_elements(pair_results[name], [1, 2]))
        modal = rotor.run_modal(speed=speed, num_modes=12)
        frequencies[name] = np.sort(modal.wn)[:4] / (2.0 * np.pi)  # Hz
    # more preload, stiffer bearings: each of the four lowest modes rises from light to medium
    # to heavy; the two lowest (the rotor rocking on the pair, in y and z; about 32 Hz with the
    # light preload) by more than 10 % a class, as the bearings' radial stiffness, about 1.5
    # and 1.3 times a class, predicts for modes that the bearings' springs govern
    assert np.all(frequencies["light"] > 10.0)
    assert np.all(frequencies["medium"] > frequencies["light"])
    assert np.all(frequencies["heavy"] > frequencies["medium"])
    assert np.all(frequencies["medium"][:2] > 1.1 * frequencies["light"][:2])
    assert np.all(frequencies["heavy"][:2] > 1.1 * frequencies["medium"][:2])
