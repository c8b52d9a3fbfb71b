"""geodesic_lod.pymeshlab: the bundled plugin loaded and every filter bound with one import, any number of
times; a pymeshlab of another version refused with both versions named."""
import pymeshlab
import pytest

import geodesic_lod.pymeshlab as registration
from conftest import bumpy_sphere


def test_every_filter_is_a_meshset_method():
    assert registration.PLUGIN.is_file()
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=bumpy_sphere(500)))
    for name in registration.FILTERS:
        assert name in pymeshlab.filter_list()
        assert callable(getattr(ms, name))
    assert ms.generate_geodesic_fps_lod(samplenum=20)["sample_num"] == 20


def test_registering_again_changes_nothing():
    before = sorted(pymeshlab.filter_list())
    registration.register()
    assert sorted(pymeshlab.filter_list()) == before


@pytest.mark.parametrize("other", ["2023.12.post3", "2025.6", "2026.7"])
def test_another_pymeshlab_is_refused_naming_both_versions(monkeypatch, other):
    monkeypatch.setattr(registration.importlib.metadata, "version", lambda name: other)
    with pytest.raises(ImportError) as e:
        registration.register()
    assert other in str(e.value) and registration.MESHLAB_VERSION in str(e.value)


def test_the_installed_pymeshlab_matches():
    assert registration._release(registration.importlib.metadata.version("pymeshlab")) == \
        registration._release(registration.MESHLAB_VERSION)
