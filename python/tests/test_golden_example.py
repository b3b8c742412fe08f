import os
import pathlib

import numpy as np
import pytest

import shadowref

SIZE = (160, 120)
GOLDEN = pathlib.Path(__file__).parent / "golden"


@pytest.fixture(scope="module")
def pumpkins():
    return shadowref.load("scenes/pumpkins.yaml", {"image.width": SIZE[0], "image.height": SIZE[1]})


def test_zpass_counts_one_too_few_inside_a_volume(pumpkins):
    zpass = shadowref.render(pumpkins, method="zpass").stencil_per_light["L0"].view(np.int8)
    zfail = shadowref.render(pumpkins, method="zfail").stencil_per_light["L0"].view(np.int8)
    truth = shadowref.oracle(pumpkins, 0)
    sure = truth.near_edge == 0
    assert np.array_equal(zfail[sure], truth.zfail[sure])  # z-fail counts what the rays count
    assert np.array_equal(zpass[sure], truth.zpass[sure])  # and z-pass what they count from the near plane
    inside = sure & (truth.zpass != truth.zfail)  # the pixels whose near-plane point is in a volume
    assert inside.mean() > 0.5 and np.all(zpass[inside] == zfail[inside] - 1)


def test_stencil_golden(pumpkins):
    stencil = shadowref.render(pumpkins, method="zfail").stencil
    golden = GOLDEN / "pumpkins-zfail-stencil.npz"
    if os.environ.get("SHADOWREF_UPDATE_GOLDENS") == "1":  # after an intended change only
        np.savez_compressed(golden, stencil=stencil)
    assert np.array_equal(stencil, np.load(golden)["stencil"])
