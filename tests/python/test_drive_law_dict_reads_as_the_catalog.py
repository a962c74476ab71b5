"""A law given to lamina.drive as a dict is read by the law reader of cell
phases and catalog entries (materials::readLawSpec): the catalog's
polyurea-gvbo keys as a dict drive exactly as the catalog entry does."""

import tomllib

import lamina


def test_a_gvbo_dict_is_the_catalog_law_with_those_keys(source_dir):
    """The dict read by the law reader of cell phases: the catalog's
    polyurea-gvbo keys as a dict drive exactly as the catalog entry."""
    catalog = tomllib.loads((source_dir / "materials" / "catalog.toml").read_text())
    entry = catalog["polyurea-gvbo"]
    law = {"law": "gvbo", "E": entry["E"], "nu": entry["nu"], "gvbo": entry["gvbo"]}
    ours = lamina.drive(law, rate=1e3, to=0.2, steps=40, unload=True)
    named = lamina.drive("polyurea-gvbo", rate=1e3, to=0.2, steps=40, unload=True)
    for name in named:
        assert ours[name].tobytes() == named[name].tobytes(), name
    assert named["sig_xx"].max() > 0
