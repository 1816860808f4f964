"""The validation manual (docs/validation.md) is current, and no row of it disagrees.

The manual is regenerated here without the optional MuJoCo section (about 10 s on one core):
every row must still have an accepted verdict (so a regression in the library turns a row of
the manual red and fails this test), and its numbers must match the committed file (so the
committed manual describes this version of the library; regenerate it with
``python -m rocking.validation --out docs/validation.md``).
"""

from pathlib import Path

import pytest

from rocking.validation import ACCEPTED, all_rows, build, parse, render

DOC = Path(__file__).resolve().parent.parent / "docs" / "validation.md"
REGENERATE = "regenerate it: python -m rocking.validation --out docs/validation.md"


@pytest.fixture(scope="module")
def committed():
    return parse(DOC.read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def fresh():
    return build(quick=False, with_peer=False)


def _close(a, b, rtol, atol=1e-12):
    if a is None or b is None:
        return a is None and b is None
    return abs(a - b) <= rtol * max(abs(a), abs(b)) + atol


def test_every_fresh_row_has_an_accepted_verdict(fresh):
    bad = [(r.id, r.status, r.case, r.detail) for r in all_rows(fresh) if r.status not in ACCEPTED]
    assert not bad, f"rows of the validation manual that now disagree: {bad}"


def test_every_committed_row_has_an_accepted_verdict(committed):
    assert len(committed) > 100, "docs/validation.md lost its tables"
    bad = {rid: row["status"] for rid, row in committed.items() if row["status"] not in ACCEPTED}
    assert not bad, f"docs/validation.md holds rows that disagree: {bad}"


def test_the_committed_manual_is_current(fresh, committed):
    rows = all_rows(fresh)
    missing = [r.id for r in rows if r.id not in committed]
    assert not missing, f"rows missing from docs/validation.md ({REGENERATE}): {missing}"
    stale = []
    for r in rows:
        old = committed[r.id]
        # a row whose published value is 0 (a difference that must vanish) holds round-off, which
        # varies between machines: it only has to stay within the row's own tolerance
        atol = r.tol if r.published == 0.0 else 1e-12
        # the manual prints 10 significant digits; thresholds are bisected to 1e-7..1e-9, and a
        # different CPU may move a bisection by a step: 1e-5 relative separates that from a change
        for key, new in (("ours", r.ours), ("published", None if r.published_label else r.published),
                         ("exact", r.exact)):
            if not _close(old[key], new, 1e-5, atol):
                stale.append((r.id, key, old[key], new))
        if old["status"] != r.status:
            stale.append((r.id, "status", old["status"], r.status))
    assert not stale, f"docs/validation.md is out of date ({REGENERATE}): {stale}"
    fresh_ids = {r.id for r in rows}
    peer_ids = {rid for rid in committed if rid.startswith("M")}
    gone = sorted(set(committed) - fresh_ids - peer_ids)
    assert not gone, f"docs/validation.md holds rows the generator no longer makes ({REGENERATE}): {gone}"


def test_the_quick_manual_keeps_the_row_ids(committed):
    # `python -m rocking.validation --quick --check docs/validation.md` compares a subset by id
    quick = all_rows(build(quick=True, with_peer=False))
    assert quick and all(r.id in committed for r in quick)
    assert all(r.status in ACCEPTED for r in quick)


def test_render_round_trips_through_parse(fresh):
    parsed = parse(render(fresh))
    rows = all_rows(fresh)
    assert set(parsed) == {r.id for r in rows}
    for r in rows:
        assert parsed[r.id]["status"] == r.status
        assert _close(parsed[r.id]["ours"], r.ours, 1e-9)


def test_a_wrong_value_turns_a_row_red():
    from rocking.validation import Row

    assert Row("x", "s", "c", "exact", published=1.0, ours=1.0 + 1e-9, tol=1e-8).status == "agrees"
    assert Row("x", "s", "c", "exact", published=1.0, ours=1.001, tol=1e-8).status == "DIFFERS"
    # a small-angle formula may be off; the library may not be off from the exact integration
    assert Row("x", "s", "c", "approx", published=1.05, exact=1.0, ours=1.0, tol=1e-6).status == \
        "approximation fails (explained)"
    assert Row("x", "s", "c", "approx", published=1.0, exact=1.0, ours=1.01, tol=1e-6).status == "DIFFERS"
    # an outside solver may differ only with a stated reason
    assert Row("x", "s", "c", "peer", ours=1.0, exact=1.5, tol=0.01).status == "DIFFERS"
    assert Row("x", "s", "c", "peer", ours=1.0, exact=1.5, tol=0.01, note="why").status == "differs (explained)"


def test_without_mujoco_the_manual_says_so(monkeypatch):
    from rocking.validation import peer

    monkeypatch.setattr(peer, "mujoco", None)
    section = peer.section(False, lambda _m: None)
    assert section.rows == [] and "not installed" in section.intro
