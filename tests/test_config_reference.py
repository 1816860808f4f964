"""docs/configuration.md is generated from the configuration schema and must be current."""

from __future__ import annotations

from pathlib import Path

from rocking.cli import config_reference as ref

PAGE = Path(__file__).resolve().parents[1] / "docs" / "configuration.md"


def test_every_key_of_every_table_has_a_unit_and_a_meaning():
    missing = [f"{name}.{r['key']}" for _, model in ((h, m) for h, m, _ in ref.TABLES)
               for _, name, table in ref.rows(model) for r in table if r["meaning"] == "?"]
    assert not missing, f"add these keys to rocking.cli.config_reference.MEANING: {missing}"


def test_the_committed_page_is_current():
    assert PAGE.read_text(encoding="utf-8") == ref.reference(), (
        "docs/configuration.md is out of date: python -m rocking.cli.config_reference --out docs/configuration.md")


def test_the_page_lists_defaults_units_and_allowed_values():
    text = ref.reference()
    assert "| `free_time_limit` | number | 60 | s | ≥ 0 |" in text
    assert "| `normal_force` | string | \"full\" |  | \"full\", \"paper\" |" in text
    assert "| `restitution` | number | omitted | – | ≥ 0, ≤ 1 |" in text
    assert "| `friction_scatter` | number | 0.2 | – | ≥ 0, < 1 |" in text
    for kind in ("harmonic", "record", "sine", "cosine", "rectangle", "ricker"):
        assert f"### `[motion ({kind})]`" in text
