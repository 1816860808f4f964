"""What people read of ``rocking paper``: paper_outcomes.md (title, summary, tables, key, link)
and the eight case figures (panel labels, one scale, markers, legends, titles).

The summary's numbers are recomputed here from the CSV the same call writes, not from the
function that wrote them, so a wrong count or a hard-coded one fails.
"""

from __future__ import annotations

import csv
import re
from pathlib import Path

import numpy as np
import pytest

from rocking.analyses import paper
from rocking.analyses.paper import PAPER_CASES

CASE_ORDER = [c.name for c in PAPER_CASES]


@pytest.fixture(scope="module")
def table():
    responses = {}
    rows = paper.run_paper_cases(responses=responses)
    return rows, responses


@pytest.fixture(scope="module")
def written(table, tmp_path_factory):
    rows, _ = table
    out = tmp_path_factory.mktemp("paper")
    csv_path, md_path = paper.write_outcome_table(rows, out)
    with csv_path.open(encoding="utf-8") as f:
        csv_rows = list(csv.DictReader(f))
    return csv_rows, md_path.read_text(encoding="utf-8"), md_path


@pytest.fixture(scope="module")
def figures(table):
    from rocking.viz.paper_figures import paper_case_figures

    _, responses = table
    return paper_case_figures(responses)


# ---------------------------------------------------------------------------------------------
# paper_outcomes.md
# ---------------------------------------------------------------------------------------------
def _section(md: str, heading: str) -> str:
    """Text of the ``## heading`` section, up to the next ``## ``."""
    start = md.index(f"## {heading}\n")
    end = md.find("\n## ", start + 1)
    return md[start: end if end >= 0 else None]


def _table_rows(section: str) -> tuple[list[str], list[list[str]]]:
    """Header cells and body rows (cells) of the Markdown table in ``section``."""
    lines = [line for line in section.splitlines() if line.startswith("|")]

    def cells(line: str) -> list[str]:
        return [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]

    return cells(lines[0]), [cells(line) for line in lines[2:]]


def _expand(fig_cell: str) -> list[str]:
    """"11a–12b" → the cases it spans; "9a, 10a" → both."""
    if "–" in fig_cell:
        first, last = fig_cell.split("–")
        return CASE_ORDER[CASE_ORDER.index(first): CASE_ORDER.index(last) + 1]
    return [c.strip() for c in fig_cell.split(",")]


def _of(csv_rows, variant):
    return [r for r in csv_rows if r["variant"] == variant]


def test_md_opens_with_a_title_and_the_summary_numbers_match_the_csv(written):
    csv_rows, md, _ = written
    assert md.splitlines()[0] == "# The paper's case studies (Figs. 9–12), rerun"
    summary = _section(md, "Summary")

    ped = _of(csv_rows, "pedestal")
    fell = [r["case"] for r in ped if r["overturned"] == "True"]
    passed = [r for r in ped if r["exceeded_alpha"] == "True"]
    peak = max(float(r["peak_rotation_over_alpha"]) for r in ped if r["overturned"] == "False")
    m = re.search(r"\*\*On the pedestal\*\*, the statue survives in (\d+) of (\d+) cases.*? passes its "
                  r"stability limit α in (\d+) of (\d+).*?largest peak is ([\d.]+)α", summary)
    assert m, summary
    assert (int(m[1]), int(m[2])) == (len(ped) - len(fell), len(ped)) == (8, 8)
    assert (int(m[3]), int(m[4])) == (len(passed), len(ped))
    assert m[5] == f"{peak:.3f}"

    alone = _of(csv_rows, "alone_infinite_friction")
    alone_fell = [r["case"] for r in alone if r["overturned"] == "True"]
    alone_passed = [r["case"] for r in alone if r["exceeded_alpha"] == "True"]
    m = re.search(r"cannot slide on\*\* \(the paper's baseline\), the statue falls in (\d+) of (\d+) cases "
                  r"\(([^)]*)\) and passes α in (\d+) of (\d+) \(([^)]*)\)", summary)
    assert m, summary
    assert (int(m[1]), int(m[2]), m[3].split(", ")) == (len(alone_fell), len(alone), alone_fell)
    assert (int(m[4]), int(m[5]), m[6].split(", ")) == (len(alone_passed), len(alone), alone_passed)

    judged = ped + alone
    hold = sum(r["agrees"] == "True" for r in judged)
    hold_alpha = sum(r["agrees_alpha_criterion"] == "True" for r in judged)
    m = re.search(r"hold in (\d+) of (\d+) if \"overturning\" means falling \(\|θ\| = π/2\), and in (\d+) of "
                  r"(\d+) if it means passing α", summary)
    assert m, summary
    assert [int(x) for x in m.groups()] == [hold, len(judged), hold_alpha, len(judged)]
    assert (hold, hold_alpha, len(judged)) == (7, 12, 16)  # regression (docs/paper-case-studies.md)

    moving = sum(r["still_moving"] == "True" for r in csv_rows)
    settled = sum(r["still_moving"] == "True" and r["settled_by_energy"] == "True" for r in csv_rows)
    assert f"- {moving} of {len(csv_rows)} runs were still moving" in summary
    assert (f"In {settled} of them the statue has less energy left than it needs to overturn, so it cannot fall "
            f"afterwards; the verdict of the other {moving - settled} covers that window only.") in summary
    # the paper's impact law, which can add energy where the pedestal slides, never settles a run
    assert settled > 0 and not any(r["settled_by_energy"] == "True" for r in csv_rows
                                   if r["variant"] == "pedestal_paper_options")
    header, body = _table_rows(_section(md, "The statue on the pedestal"))
    end = {(row[0], row[1]): row[header.index("at the end")] for row in body}
    assert end[("9a", "on pedestal (full N, Coulomb impact)")] == "moving, cannot fall"
    assert end[("9a", "on pedestal (paper: N = Mg, θ̇⁺ = rθ̇⁻)")] == "moving"


def test_md_summary_follows_the_rows(table):
    # A fall on the pedestal (made up here) must show in the summary: nothing is hard-coded.
    rows, _ = table
    changed = [dict(r) for r in rows]
    for r in changed:
        if (r["case"], r["variant"]) == ("10a", "pedestal"):
            r.update(overturned=True, overturn_time=3.0, exceeded_alpha=True, exceeded_alpha_time=2.0)
    summary = _section(paper.outcome_table_markdown(changed), "Summary")
    assert "the statue survives in 7 of 8 cases (10a) and passes its stability limit α in 1 of 8 (10a)" in summary


def test_md_key_explains_every_column_header(written):
    _, md, _ = written
    key = _section(md, "Key")
    for heading in ("The statue on the pedestal", "The statue alone on the floor"):
        header, _ = _table_rows(_section(md, heading))
        assert len(header) == 16
        for name in header:
            assert f"- **{name}**: " in key, name
    for term in ("t = 0⁺", "warn.", "agrees (π/2)", "agrees (α)"):
        assert f"- **{term}**: " in key


def test_md_tables_have_no_repeated_rows_and_cover_every_run(written):
    csv_rows, md, _ = written
    assert len(csv_rows) == len(PAPER_CASES) * len(paper.VARIANTS)  # the CSV keeps every run
    covered = []
    for heading in ("The statue on the pedestal", "The statue alone on the floor"):
        _, body = _table_rows(_section(md, heading))
        readings = [tuple(cells[1:]) for cells in body]
        assert len(set(readings)) == len(readings), "two rows read the same"
        covered += [(case, cells[1]) for cells in body for case in _expand(cells[0])]
    labels = {v: paper.VARIANT_LABELS[v] for v in paper.VARIANTS}
    assert sorted(covered) == sorted((r["case"], labels[r["variant"]]) for r in csv_rows)
    # The statue alone of 11a–12b (C4: independent of m2) is one row per run, not four.
    _, alone = _table_rows(_section(md, "The statue alone on the floor"))
    assert [cells[0] for cells in alone].count("11a–12b") == 2
    assert len(alone) == 10


def test_md_links_to_the_case_study_page(written):
    _, md, md_path = written
    m = re.search(r"\[docs/paper-case-studies\.md\]\(([^)]+)\)", md)
    assert m, "no link to docs/paper-case-studies.md"
    page = Path(__file__).parents[1] / "docs" / "paper-case-studies.md"
    assert (md_path.parent / m[1]).resolve() == page.resolve()


# ---------------------------------------------------------------------------------------------
# Figures
# ---------------------------------------------------------------------------------------------
def test_panel_labels_follow_the_paper(figures):
    assert list(figures) == CASE_ORDER
    for name, fig in figures.items():
        letter = name[-1]
        titles = [ax.get_title(loc="left") for ax in fig.axes]
        assert [t.split(" ")[0] for t in titles] == [f"({letter}.1)", f"({letter}.2)", f"({letter}.3)"], name


def test_titles_are_one_short_line_and_options_are_in_the_legend(figures):
    for name, fig in figures.items():
        title = fig._suptitle.get_text()
        assert "\n" not in title and len(title) <= 60 and title.startswith(f"Fig. {name} "), title
        assert all("\n" not in ax.get_title(loc="left") for ax in fig.axes)
        legend = " ".join(t.get_text() for t in _legends(fig)[0].get_texts())
        assert "impact='coulomb'" in legend and "impact='paper'" in legend


def test_one_vertical_scale_for_all_eight_figures(table, figures):
    _, responses = table
    theta = {fig.axes[i].get_ylim() for fig in figures.values() for i in (1, 2)}
    sliding = {fig.axes[0].get_ylim() for fig in figures.values()}
    assert len(theta) == 1 and len(sliding) == 1
    (low, high), = theta
    standing = max(r.peak_rotation / r.alpha for r in responses.values() if not r.overturned)
    assert low == -high and 1.0 < standing < high < 2.0  # every curve that stays up fits, falls leave
    (u_low, u_high), = sliding
    assert u_low == -u_high and max(float(abs(r.u).max()) for r in responses.values()) < u_high


def test_fall_is_marked_on_the_edge(table, figures):
    _, responses = table
    fallen = [(c, v) for (c, v), r in responses.items() if r.overturned]
    assert fallen == [("10b", "alone_infinite_friction")]  # regression (test_paper.py)
    ax = figures["10b"].axes[2]
    (marker,) = [line for line in ax.get_lines() if line.get_gid() == "falls"]
    (x,), (y,) = marker.get_xdata(), marker.get_ydata()
    assert x == responses[fallen[0]].overturn_time
    assert abs(y) == ax.get_ylim()[1] and not marker.get_clip_on()
    assert all(line.get_gid() != "falls" for fig in figures.values() for a in fig.axes for line in a.get_lines()
               if fig is not figures["10b"])


def test_alpha_marker_where_theta_first_exceeds_alpha(table, figures):
    _, responses = table
    n_markers = 0
    for name, fig in figures.items():
        for ax in fig.axes[1:]:
            for line in ax.get_lines():
                if line.get_gid() != "exceeds_alpha":
                    continue
                n_markers += 1
                (x,), (y,) = line.get_xdata(), line.get_ydata()
                run = [r for (c, _), r in responses.items() if c == name and r.exceeded_alpha_time == x]
                assert run, (name, x)
                r = run[0]
                first = int(np.argmax(np.abs(r.theta) > r.alpha))  # first saved sample beyond α
                assert abs(r.theta[first]) > r.alpha
                assert r.t[first - 1] <= x <= r.t[first]
                assert y == np.sign(r.theta[first])
    # 10a, 10b, 11a, 11b, 12a, 12b: the statue alone with μ = ∞; none on the pedestal.
    assert n_markers == sum(r.exceeded_alpha_time is not None for r in responses.values()) == 6


def test_statue_alone_sliding_is_plotted(table, figures):
    _, responses = table
    for name, fig in figures.items():
        u = responses[(name, "alone_floor_friction")].u
        lines = [line for line in fig.axes[0].get_lines()
                 if line.get_label().startswith("alone, on the pedestal's floor")]
        assert len(lines) == 1 and np.array_equal(lines[0].get_ydata(), u), name
    assert responses[("10b", "alone_floor_friction")].u.max() > 0.04  # the curve is not flat


def _legends(fig):
    return [leg for sub in [fig, *fig.subfigs] for leg in sub.legends] + [
        ax.get_legend() for ax in fig.axes if ax.get_legend() is not None
    ]


def test_legends_cover_no_data(figures):
    for name, fig in figures.items():
        fig.draw_without_rendering()  # runs the constrained layout
        legends = _legends(fig)
        assert len(legends) == 1 and all(ax.get_legend() is None for ax in fig.axes), name
        box = legends[0].get_window_extent()
        for ax in fig.axes:
            assert not box.overlaps(ax.get_window_extent()), (name, ax.get_title(loc="left"))
