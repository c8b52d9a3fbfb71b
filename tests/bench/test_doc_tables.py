"""bench/doc_tables.py: the anchor pages' tables are their saved rows, written between markers, and the
committed pages agree with the committed rows."""
import json
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import doc_tables  # noqa: E402

DOCS = ROOT / "docs"


def test_the_committed_pages_tables_are_their_saved_rows():
    pages = doc_tables.tables(DOCS)
    assert set(pages) == {"height_field.md", "mesh_lod.md", "airborne_classes.md"}
    for page, tables in pages.items():
        text = (DOCS / page).read_text()
        marked = doc_tables.MARKED.findall(text)
        assert marked, f"{page} has no marked table"
        assert doc_tables.fill(text, tables, page) == text, f"{page}: a table differs from docs/*.json"


def mesh_rows():
    rows = [dict(model="m", rate=1.0, method="input", vertices=100, mean=0.0, max=0.0, meshlab_max=0.0,
                 non_manifold_edges=0, boundary_edges=4, seconds=0.0)]
    for i, method in enumerate(m for _, a, b in doc_tables.GAP for m in (a, b)):
        for rate in (0.1, 0.05):
            rows.append(dict(model="m", rate=rate, method=method, vertices=int(1000 * rate), mean=(1 + i) * rate,
                             max=10 * rate, meshlab_max=11 * rate, non_manifold_edges=0, boundary_edges=2,
                             seconds=1.0))
    return rows


def test_a_page_gets_its_rows_between_its_markers_and_keeps_its_prose(tmp_path):
    rows = mesh_rows()
    (tmp_path / "mesh_lod.md").write_text("# Meshes\n\nprose before\n\n<!-- table: m -->\nSTALE\n<!-- end table -->\n\n"
                                          "between\n\n<!-- table: gap -->\n<!-- end table -->\nafter\n")
    doc_tables.publish("mesh_lod", rows, docs=tmp_path)
    text = (tmp_path / "mesh_lod.md").read_text()
    assert "STALE" not in text and all(s in text for s in ("prose before", "between", "after"))
    body = text.split("<!-- table: m -->\n")[1].split("<!-- end table -->")[0].splitlines()
    assert len(body) == 2 + len(rows)  # heading, rule, a line a row
    assert all(line.count("|") == len(doc_tables.MESH) + 1 for line in body)
    gap = text.split("<!-- table: gap -->\n")[1].split("<!-- end table -->")[0].splitlines()
    assert len(gap) == 2 + 2  # two rates below 1
    assert json.loads((tmp_path / "mesh_lod.json").read_text()) == rows
    assert (tmp_path / "images" / "mesh_lod_error.png").stat().st_size > 0
    again = text
    doc_tables.refresh(tmp_path)
    assert (tmp_path / "mesh_lod.md").read_text() == again  # rewriting from the same rows changes nothing


def test_a_marker_without_saved_rows_is_an_error(tmp_path):
    (tmp_path / "mesh_lod.json").write_text(json.dumps(mesh_rows()))
    (tmp_path / "mesh_lod.md").write_text("<!-- table: no such model -->\n<!-- end table -->\n")
    with pytest.raises(KeyError, match="no such model"):
        doc_tables.refresh(tmp_path)
