"""PDF report on A4 pages, drawn with matplotlib's PdfPages (no extra dependency).

A small flow layout: the content becomes blocks (headings, paragraphs, tables, figures) placed
top to bottom on A4 pages. A paragraph may continue on the next page; a table never splits
(unless it is taller than a whole page); a figure shrinks to fit what is left of a page, down to
the smallest height at which its labels stay apart (:data:`FIGURE_HEIGHTS`), and stays on the
page of the paragraph that discusses it; a heading stays with what follows it. Of a few figure
sizes and two places of the key figures, the layout with the fewest pages, then the fullest
emptiest page, wins. Every page has a footer with the library version, the date, the input
file's name and short SHA-256, and the page number.

Lengths are in points (1/72 in) from the bottom-left corner of the page.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import matplotlib.image as mpimg
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.backends.backend_pdf import PdfPages
from matplotlib.figure import Figure
from matplotlib.font_manager import FontProperties
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle
from matplotlib.textpath import TextToPath
from matplotlib.transforms import Affine2D

from .content import FAIL, NOT_APPLICABLE, NOT_CHECKED, PASS, UNDETERMINED, DataTable, ReportContent

MM = 72 / 25.4
PAGE_WIDTH, PAGE_HEIGHT = 210 * MM, 297 * MM  # A4
MARGIN_X = 18 * MM
FRAME_TOP = PAGE_HEIGHT - 16 * MM
FRAME_BOTTOM = 22 * MM  # the footer sits below
FRAME_WIDTH = PAGE_WIDTH - 2 * MARGIN_X
FRAME_HEIGHT = FRAME_TOP - FRAME_BOTTOM
FIGURE_DPI = 200
LEADING = 1.3  # line height / font size

SIZES = {"title": 15.0, "h": 11.0, "body": 8.8, "verdict": 10.0, "table": 8.2, "caption": 8.0, "footer": 6.8}
VERDICT_COLORS = {  # (background, bar, text)
    "safe": ("#eef7ee", "#2d7d46", "#1f5c30"),
    "fails": ("#fbeceb", "#c0392b", "#8b1a10"),
    "stopped": ("#fff6e5", "#d68910", "#7a4a00"),
}
RESULT_STYLES = {  # text, colour, bold
    PASS: ("pass", "#1f7a3a", True),
    FAIL: ("FAIL", "#c0392b", True),
    UNDETERMINED: ("undetermined", "#b36b00", True),
    NOT_CHECKED: ("not checked", "0.45", False),
    NOT_APPLICABLE: ("n/a", "0.45", False),
}
#: (preferred, smallest) height in inches of each figure at the frame's width: below the smallest
#: the response's stacked y labels run into each other.
FIGURE_HEIGHTS = ((5.6, 4.6), (3.3, 2.4))
#: Scales of the preferred figure heights the layout tries.
FIGURE_SCALES = (1.0, 0.93, 0.86, 0.8)

_TEXT_TO_PATH = TextToPath()


# ------------------------------------------------------------------------------ measuring text
@lru_cache(maxsize=50_000)
def text_width(text: str, size: float, bold: bool = False) -> float:
    """Width of ``text`` set in the default sans-serif font at ``size`` pt, in pt."""
    prop = FontProperties(size=size, weight="bold" if bold else "normal")
    width, _, _ = _TEXT_TO_PATH.get_text_width_height_descent(text, prop, ismath=False)
    return float(width)


def _break_long_word(word: str, width: float, size: float, bold: bool) -> tuple[str, str]:
    """Split a word too wide for a line (a path, a hash) where it fits, after a '/' or '_' if one
    is not too far back."""
    lo, hi = 1, len(word)
    while lo < hi:  # the longest prefix that fits
        mid = (lo + hi + 1) // 2
        if text_width(word[:mid], size, bold) <= width:
            lo = mid
        else:
            hi = mid - 1
    cut = lo
    for sep in "/\\_-.":
        at = word.rfind(sep, 0, lo)
        if at >= lo // 2:
            cut = at + 1
            break
    return word[:cut], word[cut:]


def wrap(text: str, width: float, size: float, bold: bool = False, first_width: float | None = None) -> list[str]:
    """Lines of ``text`` no wider than ``width`` pt (the first no wider than ``first_width``).
    Breaks at spaces, and inside words longer than a line."""
    lines: list[str] = []
    for paragraph in text.split("\n"):
        line = ""
        for word in paragraph.split(" "):
            limit = first_width if (first_width is not None and not lines) else width
            candidate = f"{line} {word}" if line else word
            if text_width(candidate, size, bold) <= limit:
                line = candidate
                continue
            if line:
                lines.append(line)
                limit = width
            while word and text_width(word, size, bold) > limit:
                head, word = _break_long_word(word, limit, size, bold)
                lines.append(head)
                limit = width
            line = word
        lines.append(line)
    return lines


def _line_height(size: float) -> float:
    return size * LEADING


# ------------------------------------------------------------------------------------ drawing
def _pt_transform(page: Figure):
    """Points from the bottom-left corner of the page."""
    return Affine2D().scale(1 / 72) + page.dpi_scale_trans


def _text(page: Figure, x: float, y: float, text: str, *, size: float, bold: bool = False, color="black",
          ha: str = "left", italic: bool = False) -> None:
    page.text(x, y, text, transform=_pt_transform(page), fontsize=size, fontweight="bold" if bold else "normal",
              fontstyle="italic" if italic else "normal", color=color, ha=ha, va="baseline", parse_math=False)


def _hline(page: Figure, x0: float, x1: float, y: float, *, color="0.8", lw: float = 0.5) -> None:
    page.add_artist(Line2D([x0, x1], [y, y], transform=_pt_transform(page), color=color, lw=lw))


def _rect(page: Figure, x: float, y: float, w: float, h: float, color) -> None:
    page.add_artist(Rectangle((x, y), w, h, transform=_pt_transform(page), facecolor=color, edgecolor="none",
                              zorder=0))


# ------------------------------------------------------------------------------------- blocks
@dataclass
class Block:
    """Something placed on a page, ``width`` pt wide from ``x``. ``keep_with_next``: never the
    last thing on a page."""

    space_before: float = 0.0
    space_after: float = 0.0
    keep_with_next: bool = False
    x: float = MARGIN_X  # left edge, pt
    width: float = FRAME_WIDTH  # pt

    def height(self) -> float:
        raise NotImplementedError

    def min_height(self) -> float:
        """The least of it that may start a page's last part."""
        return self.height()

    def draw(self, page: Figure, top: float, height: float) -> None:
        raise NotImplementedError


@dataclass
class Heading(Block):
    text: str = ""
    size: float = SIZES["h"]
    rule: bool = True

    def __post_init__(self):
        self.lines = wrap(self.text, self.width, self.size, bold=True)
        self.keep_with_next = True

    def height(self) -> float:
        return self.space_before + len(self.lines) * _line_height(self.size) + 3.0 + self.space_after

    def draw(self, page, top, height):
        y = top - self.space_before
        for line in self.lines:
            y -= _line_height(self.size)
            _text(page, self.x, y + 0.25 * self.size, line, size=self.size, bold=True)
        if self.rule:
            _hline(page, self.x, self.x + self.width, y - 1.0, color="0.75", lw=0.6)


@dataclass
class Paragraph(Block):
    """Wrapped text; a bullet hangs, a ``box`` (verdict class) draws a coloured panel behind."""

    text: str = ""
    size: float = SIZES["body"]
    bold: bool = False
    color: str = "black"
    bullet: bool = False
    hanging: bool = False  # indented like a bullet's text: the rest of a bullet split across pages
    box: str | None = None
    lines: list[str] = field(default_factory=list)

    def __post_init__(self):
        if not self.lines:
            self.lines = wrap(self.text, self._text_width(), self.size, self.bold)

    def _indent(self) -> float:
        return 11.0 if (self.bullet or self.hanging) else (12.0 if self.box else 0.0)

    def _text_width(self) -> float:
        return self.width - self._indent() - (8.0 if self.box else 0.0)

    def _pad(self) -> float:
        return 6.0 if self.box else 0.0

    def height(self) -> float:
        return self.space_before + len(self.lines) * _line_height(self.size) + 2 * self._pad() + self.space_after

    def min_height(self) -> float:
        if self.keep_with_next or self.box:
            return self.height()
        return self.space_before + min(2, len(self.lines)) * _line_height(self.size)

    def split(self, available: float) -> tuple[Paragraph, Paragraph] | None:
        """The lines that fit in ``available`` pt and the rest, keeping two lines on each side."""
        if self.box or self.keep_with_next:
            return None
        fit = int((available - self.space_before) // _line_height(self.size))
        fit = min(fit, len(self.lines) - 2)
        if fit < 2:
            return None
        style = {"text": self.text, "size": self.size, "bold": self.bold, "color": self.color, "x": self.x,
                 "width": self.width}
        head = Paragraph(**style, bullet=self.bullet, hanging=self.hanging, lines=self.lines[:fit],
                         space_before=self.space_before)
        tail = Paragraph(**style, hanging=self.bullet or self.hanging, lines=self.lines[fit:],
                         space_after=self.space_after)
        return head, tail

    def draw(self, page, top, height):
        y = top - self.space_before
        pad = self._pad()
        if self.box:
            background, bar, _ = VERDICT_COLORS[self.box]
            box_h = len(self.lines) * _line_height(self.size) + 2 * pad
            _rect(page, self.x, y - box_h, self.width, box_h, background)
            _rect(page, self.x, y - box_h, 4.0, box_h, bar)
        y -= pad
        indent = self._indent()
        for i, line in enumerate(self.lines):
            y -= _line_height(self.size)
            base = y + 0.25 * self.size
            if self.bullet and i == 0:
                _text(page, self.x + 2.0, base, "•", size=self.size, color=self.color)
            _text(page, self.x + indent, base, line, size=self.size, bold=self.bold, color=self.color)


@dataclass
class Cell:
    text: str
    color: str = "black"
    bold: bool = False


@dataclass
class Table(Block):
    """Rows of cells in columns of the given width fractions; an optional header row repeats
    when a table taller than a page must split."""

    rows: list[list[Cell]] = field(default_factory=list)
    widths: Sequence[float] = (0.45, 0.55)
    header: list[str] | None = None
    size: float = SIZES["table"]
    pad: float = 2.2

    def __post_init__(self):
        self._cells = [self._wrap_row(row) for row in self.rows]
        self._header = self._wrap_row([Cell(h, "0.3", True) for h in self.header]) if self.header else None

    def _column_widths(self) -> list[float]:
        total = sum(self.widths)
        return [self.width * w / total for w in self.widths]

    def _wrap_row(self, row: list[Cell]) -> list[tuple[Cell, list[str]]]:
        return [(c, wrap(c.text, w - 6.0, self.size, c.bold)) for c, w in zip(row, self._column_widths())]

    def _row_height(self, wrapped) -> float:
        return max(len(lines) for _, lines in wrapped) * _line_height(self.size) + 2 * self.pad

    def height(self) -> float:
        rows = ([self._header] if self._header else []) + self._cells
        return self.space_before + sum(self._row_height(r) for r in rows) + self.space_after

    def split(self, available: float) -> tuple[Table, Table] | None:
        """Rows that fit and the rest (only for a table taller than a page)."""
        used = self.space_before + (self._row_height(self._header) if self._header else 0.0)
        n = 0
        for wrapped in self._cells:
            used += self._row_height(wrapped)
            if used > available:
                break
            n += 1
        if n == 0 or n == len(self.rows):
            return None
        common = {"widths": self.widths, "header": self.header, "size": self.size, "pad": self.pad, "x": self.x,
                  "width": self.width}
        return (Table(rows=self.rows[:n], space_before=self.space_before, **common),
                Table(rows=self.rows[n:], space_after=self.space_after, **common))

    def draw(self, page, top, height):
        y = top - self.space_before
        xs = [self.x]
        for w in self._column_widths():
            xs.append(xs[-1] + w)
        rows = ([self._header] if self._header else []) + self._cells
        for k, wrapped in enumerate(rows):
            h = self._row_height(wrapped)
            for (cell, lines), x in zip(wrapped, xs):
                line_y = y - self.pad
                for line in lines:
                    line_y -= _line_height(self.size)
                    _text(page, x, line_y + 0.25 * self.size, line, size=self.size, bold=cell.bold, color=cell.color)
            y -= h
            header_row = k == 0 and self._header is not None
            _hline(page, self.x, xs[-1], y, color="0.55" if header_row else "0.85", lw=0.7 if header_row else 0.4)


@dataclass
class Columns(Block):
    """Two stacks of blocks side by side (each built for half the width); never split."""

    left: list[Block] = field(default_factory=list)
    right: list[Block] = field(default_factory=list)

    def height(self) -> float:
        return self.space_before + max(sum(b.height() for b in side) for side in (self.left, self.right)) \
            + self.space_after

    def draw(self, page, top, height):
        for side in (self.left, self.right):
            y = top - self.space_before
            for b in side:
                b.draw(page, y, b.height())
                y -= b.height()


#: Gap between two columns, pt.
COLUMN_GAP = 16.0


def fit_ylabels(fig: Figure) -> None:
    """Break onto two lines each y label taller than its axes: the labels of stacked panels in a
    short figure would run into each other."""
    canvas = fig.canvas if hasattr(fig.canvas, "get_renderer") else FigureCanvasAgg(fig)
    fig.draw_without_rendering()  # runs the layout, so the extents below are final
    renderer = canvas.get_renderer()
    for ax in fig.axes:
        label = ax.yaxis.label
        words = label.get_text().split(" ")
        if len(words) < 2 or "\n" in label.get_text():
            continue
        if label.get_window_extent(renderer).height <= ax.get_window_extent(renderer).height:
            continue
        half = len(label.get_text()) / 2
        cut = min(range(1, len(words)), key=lambda k: abs(len(" ".join(words[:k])) - half))
        label.set_text(" ".join(words[:cut]) + "\n" + " ".join(words[cut:]))


@dataclass
class FigureBlock(Block):
    """A matplotlib figure redrawn at the frame's width and the height the page leaves, then
    embedded as a PNG, with its numbered caption below."""

    figure: Figure | None = None
    label: str = ""
    caption: str = ""
    preferred: float = 3.3  # in
    smallest: float = 2.5  # in

    def __post_init__(self):
        size = SIZES["caption"]
        self._label_width = text_width(self.label + " ", size, bold=True)
        self._caption_lines = wrap(self.caption, self.width, size, first_width=self.width - self._label_width)

    def _caption_height(self) -> float:
        return 4.0 + len(self._caption_lines) * _line_height(SIZES["caption"])

    def height(self) -> float:
        return self.space_before + self.preferred * 72 + self._caption_height() + self.space_after

    def min_height(self) -> float:
        return self.space_before + min(self.smallest, self.preferred) * 72 + self._caption_height() + self.space_after

    def draw(self, page, top, height):
        image_h = height - self.space_before - self._caption_height() - self.space_after
        image_top = top - self.space_before
        self.figure.set_size_inches(self.width / 72, image_h / 72)
        fit_ylabels(self.figure)
        buf = io.BytesIO()
        self.figure.savefig(buf, format="png", dpi=FIGURE_DPI, metadata={"Software": None})
        buf.seek(0)
        pixels = mpimg.imread(buf, format="png")
        ax = page.add_axes((self.x / PAGE_WIDTH, (image_top - image_h) / PAGE_HEIGHT,
                            self.width / PAGE_WIDTH, image_h / PAGE_HEIGHT))
        ax.imshow(pixels, interpolation="none", aspect="auto")
        ax.set_axis_off()
        size = SIZES["caption"]
        y = image_top - image_h - 4.0
        for i, line in enumerate(self._caption_lines):
            y -= _line_height(size)
            base = y + 0.25 * size
            if i == 0:
                _text(page, self.x, base, self.label, size=size, bold=True, color="0.2")
                _text(page, self.x + self._label_width, base, line, size=size, color="0.2")
            else:
                _text(page, self.x, base, line, size=size, color="0.2")


# ------------------------------------------------------------------------------------- content
def _table(rows: Sequence[tuple[str, str]], *, space_after: float = 6.0, x: float = MARGIN_X,
           width: float = FRAME_WIDTH) -> Table:
    """A (name, value) table whose name column is as wide as its longest name, within 30–55 %."""
    longest = max((text_width(k, SIZES["table"]) for k, _ in rows), default=0.0) + 8.0
    share = min(0.55, max(0.3, longest / width))
    return Table(rows=[[Cell(k, "0.35"), Cell(v)] for k, v in rows], widths=(share, 1 - share),
                 space_after=space_after, x=x, width=width)


#: The input tables short enough to stand two by two, side by side.
SIDE_BY_SIDE_INPUTS = ("Statue", "Pedestal", "Motion", "Options")


def _inputs(content: ReportContent) -> list[Block]:
    """The input tables two by two, side by side (statue | pedestal, motion | options); other
    tables (a caller's, which may hold long text) full width."""
    half = (FRAME_WIDTH - COLUMN_GAP) / 2
    sections = [(k, v) for k, v in content.inputs.items() if k in SIDE_BY_SIDE_INPUTS]
    out: list[Block] = []
    for i in range(0, len(sections), 2):
        sides = []
        for j, (section, rows) in enumerate(sections[i:i + 2]):
            x = MARGIN_X + j * (half + COLUMN_GAP)
            sides.append([Heading(text=f"Inputs: {section}", space_before=6.0, space_after=2.0, x=x, width=half),
                          _table(rows, x=x, width=half)])
        out.append(Columns(left=sides[0], right=sides[1] if len(sides) > 1 else []))
    for section, rows in content.inputs.items():
        if section not in SIDE_BY_SIDE_INPUTS:
            out += [Heading(text=f"Inputs: {section}", space_before=6.0, space_after=2.0), _table(rows)]
    return out


def _data_table(table: DataTable) -> list[Block]:
    """A titled table with a header row (a row per block of a stack, say): under the key figures
    a sub-heading, among the inputs a heading like theirs."""
    if table.place == "inputs":
        title = Heading(text=table.heading, space_before=6.0, space_after=2.0)
    else:
        title = Heading(text=table.heading, size=SIZES["body"] + 0.6, rule=False, space_before=4.0, space_after=1.0)
    return [title,
            Table(rows=[[Cell(c) for c in row] for row in table.rows], widths=table.widths,
                  header=list(table.header), space_after=6.0)]


def _check_rows(content: ReportContent) -> list[list[Cell]]:
    rows = []
    for c in content.checks:
        text, color, bold = RESULT_STYLES[c.result]
        rows.append([Cell(c.name), Cell(c.value), Cell(c.limit), Cell(text, color, bold)])
    return rows


def _figure_heights(number: int, fig: Figure) -> tuple[float, float]:
    """(preferred, smallest) height, in: the response and energy figures' own, or another
    figure's aspect at the frame's width (it may shrink by a quarter)."""
    if number <= len(FIGURE_HEIGHTS):
        return FIGURE_HEIGHTS[number - 1]
    width, height = fig.get_size_inches()
    preferred = min(FRAME_WIDTH / 72 * height / width, 0.8 * FRAME_HEIGHT / 72)
    return preferred, 0.75 * preferred


def blocks(content: ReportContent, figures: Sequence[Figure], verdict_class: str = "safe",
           figure_scale: float = 1.0, key_figures_first: bool = False) -> list[Block]:
    """The report as blocks, in reading order; ``figures`` match ``content.figures``, drawn at
    ``figure_scale`` times their preferred height (not below their smallest). The key figures
    follow the first figure, or come before it with ``key_figures_first``."""
    out: list[Block] = [
        Heading(text=content.title, size=SIZES["title"], rule=False, space_after=4.0),
        Paragraph(text=content.verdict, size=SIZES["verdict"], bold=True, box=verdict_class,
                  color=VERDICT_COLORS[verdict_class][2], space_after=8.0),
        Heading(text="Checks", space_before=4.0, space_after=2.0),
        Table(rows=_check_rows(content), widths=(0.37, 0.3, 0.18, 0.15), header=["check", "value", "limit", "result"],
              space_after=6.0),
    ]
    # warnings right under the checks: short when all is well, and not to be missed when not
    out.append(Heading(text="Warnings", space_before=4.0, space_after=2.0))
    if content.warnings:
        out += [Paragraph(text=w, bullet=True, space_after=2.0) for w in content.warnings]
    else:
        out.append(Paragraph(text="None: every assumption of the model held during the run.", space_after=4.0))
    key_figures = [Heading(text="Key figures", space_before=4.0, space_after=2.0), _table(content.key_figures)]
    for table in content.tables_at("results"):
        key_figures += _data_table(table)
    if key_figures_first or not content.figures:
        out += key_figures
    for text, fig in zip(content.figures, figures):
        preferred, smallest = _figure_heights(text.number, fig)
        out += [
            Heading(text=text.heading, space_before=4.0, space_after=2.0),
            Paragraph(text=text.discussion, keep_with_next=True, space_after=4.0),
            FigureBlock(figure=fig, label=f"Figure {text.number}:", caption=text.caption,
                        preferred=max(smallest, figure_scale * preferred), smallest=smallest, space_after=6.0),
        ]
        if text.number == 1 and not key_figures_first:  # after the picture of the motion they sum up
            out += key_figures
    for table in content.tables_at("inputs"):
        out += _data_table(table)
    out += _inputs(content)
    out.append(Heading(text="Model assumptions", space_before=6.0, space_after=2.0))
    out += [Paragraph(text=a, bullet=True, space_after=2.0) for a in content.assumptions]
    if content.symbols:
        out.append(Heading(text="Symbols", space_before=6.0, space_after=2.0))
        half = (len(content.symbols) + 1) // 2
        left, right = content.symbols[:half], content.symbols[half:] + [("", "")] * (2 * half - len(content.symbols))
        out.append(Table(rows=[[Cell(a, bold=True), Cell(b, "0.2"), Cell(c, bold=True), Cell(d, "0.2")]
                               for (a, b), (c, d) in zip(left, right)], widths=(0.09, 0.41, 0.09, 0.41)))
    if content.events:
        out.append(Paragraph(text=f"The {len(content.events)} events of the run (impacts and changes of regime) are "
                                  "listed in report.html, written with this file.", color="0.35", space_before=6.0))
    return out


# ---------------------------------------------------------------------------------- pagination
@dataclass
class Placed:
    block: Block
    top: float
    height: float


def _lead(queue: list[Block], k: int) -> float:
    """Height needed on a page to start ``queue[k]`` there, with what it keeps with."""
    if k >= len(queue):
        return 0.0
    b = queue[k]
    if b.keep_with_next:
        return b.height() + _lead(queue, k + 1)
    return b.min_height()


def paginate(items: Sequence[Block]) -> list[list[Placed]]:
    """Place the blocks on pages of height :data:`FRAME_HEIGHT`, in order."""
    pages: list[list[Placed]] = [[]]
    queue = list(items)
    used = 0.0

    def place(block: Block, height: float) -> None:
        nonlocal used
        pages[-1].append(Placed(block, FRAME_TOP - used, height))
        used += height

    def new_page() -> None:
        nonlocal used
        pages.append([])
        used = 0.0

    while queue:
        block = queue.pop(0)
        available = FRAME_HEIGHT - used
        after = _lead(queue, 0) if block.keep_with_next else 0.0
        if block.height() + after <= available:
            place(block, block.height())
            continue
        if isinstance(block, FigureBlock) and block.min_height() <= available:
            place(block, available)  # shrunk to what the page leaves
            continue
        if isinstance(block, Paragraph):
            parts = block.split(available)
            if parts:
                place(parts[0], parts[0].height())
                queue.insert(0, parts[1])
                new_page()
                continue
        if not pages[-1]:  # taller than an empty page: split it, or shrink it onto the page
            parts = block.split(available) if isinstance(block, (Table, Paragraph)) else None
            if parts:
                place(parts[0], parts[0].height())
                queue.insert(0, parts[1])
            else:
                place(block, min(block.height(), available))
            new_page()
            continue
        new_page()
        queue.insert(0, block)
    if not pages[-1]:
        pages.pop()
    return pages


def page_fill(page: list[Placed]) -> float:
    """Fraction of the frame's height a page uses."""
    return sum(p.height for p in page) / FRAME_HEIGHT


# --------------------------------------------------------------------------------------- output
def _footer(page: Figure, content: ReportContent, number: int, count: int) -> None:
    size = SIZES["footer"]
    rule = FRAME_BOTTOM - 5.0
    y = rule - 9.0
    _hline(page, MARGIN_X, MARGIN_X + FRAME_WIDTH, rule, color="0.75", lw=0.5)
    numbering = f"page {number} of {count}"
    _text(page, MARGIN_X + FRAME_WIDTH, y, numbering, size=size, color="0.35", ha="right")
    text = content.provenance.footer if content.provenance is not None else "rocking"
    room = FRAME_WIDTH - text_width(numbering, size) - 12.0
    for i, line in enumerate(wrap(text, room, size)[:2]):
        _text(page, MARGIN_X, y - i * _line_height(size), line, size=size, color="0.35")


def layout(content: ReportContent, figures: Sequence[Figure], verdict_class: str = "safe") -> list[list[Placed]]:
    """The pages, for the figure scale of :data:`FIGURE_SCALES` and the place of the key figures
    (after the first figure, or before it when the first figure's section would leave the first
    page half empty) that give the fewest pages, then the fullest emptiest page."""
    best, best_key = None, None
    for key_figures_first in (False, True):
        for scale in FIGURE_SCALES:
            pages = paginate(blocks(content, figures, verdict_class, figure_scale=scale,
                                    key_figures_first=key_figures_first))
            key = (len(pages), -round(min(page_fill(p) for p in pages), 2))
            if best_key is None or key < best_key:
                best, best_key = pages, key
    return best


def render_pages(content: ReportContent, figures: Sequence[Figure], verdict_class: str = "safe") -> list[Figure]:
    """The A4 pages as matplotlib Figures."""
    pages = layout(content, figures, verdict_class)
    out = []
    for number, placed in enumerate(pages, start=1):
        page = Figure(figsize=(PAGE_WIDTH / 72, PAGE_HEIGHT / 72))
        for p in placed:
            p.block.draw(page, p.top, p.height)
        _footer(page, content, number, len(pages))
        out.append(page)
    return out


def write_pdf(content: ReportContent, figures: Sequence[Figure], path: str | Path, *,
              verdict_class: str = "safe") -> Path:
    """Write the report on A4 pages; ``figures`` are the matplotlib figures of
    ``content.figures``, in order (they are resized). Returns the path."""
    path = Path(path)
    version = content.provenance.version if content.provenance is not None else ""
    with PdfPages(path, metadata={"Title": content.title, "Creator": f"rocking {version}".strip(),
                                  "CreationDate": None}) as pdf:
        for page in render_pages(content, figures, verdict_class):
            pdf.savefig(page)
    return path
