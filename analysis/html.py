"""index.html: summary.md's findings (the answer and answer.png first, then
the figures that answer a findings line, regime-<target>.png), one table of
contents, the other figures (the best of each family first) and the rest of
summary.md; all-methods.html: the charts of every method, one per scene
(54 look-alike curves would bury the first page). Each figure has a caption
(analysis/captions.py), never its file name.

summary.md is rendered here (headings, lists, tables, paragraphs, `code`
and **bold**: what summary.py writes); everything is HTML-escaped. A small
script marks each image data-state="loaded" or "broken", so a headless
browser can check that the page shows every figure.
"""
import html
import re

from analysis import captions

MARK_IMAGES = """<script>
function mark(img) { img.dataset.state = img.complete && img.naturalWidth > 0 ? "loaded" : "broken"; }
window.addEventListener("load", function () { document.querySelectorAll("img").forEach(mark); });
</script>"""
STYLE = """<style>
body { font-family: sans-serif; margin: 2em; max-width: 1400px; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; font-size: 0.85em; }
td, th { border: 1px solid #ccc; padding: 2px 6px; }
th { background: #f0f0f0; }
img { max-width: 100%; border: 1px solid #eee; }
figure { margin: 1em 0 2em; }
figcaption { max-width: 60em; color: #333; }
</style>"""

# ![caption](file.png) on a line of its own
IMAGE = re.compile(r"!\[([^\]]*)\]\(([^)\s]+)\)")


def inline(text):
    text = html.escape(text, quote=False)
    text = re.sub(r"`([^`]+)`", r"<code>\1</code>", text)
    text = re.sub(r"\[([^\]]+)\]\((#[a-z0-9-]+)\)", r'<a href="\2">\1</a>', text)
    return re.sub(r"\*\*([^*]+)\*\*", r"<strong>\1</strong>", text)


def _cells(line):
    # split on '|' that is not escaped as '\|'
    parts = re.split(r"(?<!\\)\|", line.strip().strip("|"))
    return [p.strip().replace("\\|", "|") for p in parts]


def _sublist(items):
    return "<ul>" + "".join(f"<li>{inline(i)}</li>" for i in items) + "</ul>" if items else ""


def markdown_to_html(markdown):
    out, table, bullets, paragraph = [], [], [], []

    def flush():
        if table:
            rows = [_cells(line) for line in table if not re.fullmatch(r"\|[-|]*\|", line.strip())]
            out.append("<table>")
            out.append("<tr>" + "".join(f"<th>{inline(c)}</th>" for c in rows[0]) + "</tr>")
            out.extend("<tr>" + "".join(f"<td>{inline(c)}</td>" for c in r) + "</tr>" for r in rows[1:])
            out.append("</table>")
        if bullets:
            out.append("<ul>" + "".join(f"<li>{inline(b)}" + _sublist(subs) + "</li>" for b, subs in bullets)
                       + "</ul>")
        if paragraph:
            out.append(f"<p>{inline(' '.join(paragraph))}</p>")
        table.clear()
        bullets.clear()
        paragraph.clear()

    for line in markdown.splitlines():
        heading = re.match(r"(#{1,6}) (.*)", line)
        if heading:
            flush()
            level = len(heading.group(1))
            out.append(f"<h{level} id=\"{slug(heading.group(2))}\">{inline(heading.group(2))}</h{level}>")
        elif IMAGE.fullmatch(line.strip()):
            flush()  # a figure on its own line: summary.md's answer.png
            alt, src = IMAGE.fullmatch(line.strip()).groups()
            out.append(_figure(src, alt))
        elif line.startswith("|"):
            table.append(line)
        elif line.startswith("- "):
            bullets.append((line[2:], []))
        elif line.startswith("  - ") and bullets:
            bullets[-1][1].append(line[4:])  # one level down: the findings' per-scene lines
        elif not line.strip():
            flush()
        else:
            paragraph.append(line.strip())
    flush()
    return "\n".join(out)


def slug(heading):
    """The anchor of a heading (as summary.py's contents link to it)."""
    return re.sub(r"[^a-z0-9]+", "-", heading.lower()).strip("-")


# figures in this order: the best of each family first
FIGURE_ORDER = ("work-precision-best-", "convergence-", "tolerance-", "drift-")
ALL_METHODS_PAGE = "all-methods.html"
# figures that answer a findings line: shown inside the findings, after them
FINDINGS_FIGURES = ("regime-",)


def ordered_figures(names):
    def rank(name):
        return next((i for i, p in enumerate(FIGURE_ORDER) if name.startswith(p)), len(FIGURE_ORDER))
    return sorted(names, key=lambda n: (rank(n), names.index(n)))


def all_methods(name):
    """A chart with a curve for every method of a scene (work-precision-<scene>.png): all-methods.html's."""
    return name.startswith("work-precision-") and not name.startswith("work-precision-best-")


def inline_figures(markdown):
    """The figures summary.md shows itself (![caption](name) lines), drawn where they stand."""
    return {IMAGE.fullmatch(line.strip()).group(2) for line in markdown.splitlines() if IMAGE.fullmatch(line.strip())}


def split_summary(markdown):
    """(findings, rest): the '## Findings' section, and everything after summary.md's own contents."""
    lines = markdown.splitlines()
    heads = [i for i, line in enumerate(lines) if line.startswith("## ")]
    if not heads or lines[heads[0]] != "## Findings":
        return "", markdown
    end = heads[1] if len(heads) > 1 else len(lines)
    rest = lines[end:]
    if rest and rest[0] == "## Contents":
        later = [i for i, line in enumerate(rest) if line.startswith("## ")][1:]
        rest = rest[later[0]:] if later else []
    return "\n".join(lines[heads[0]:end]), "\n".join(rest)


def _figure(name, caption=None):
    caption = caption or captions.caption(name)
    link, alt = html.escape(name, quote=True), html.escape(caption, quote=True)
    return f"<figure><img src=\"{link}\" alt=\"{alt}\"><figcaption>{inline(caption)}</figcaption></figure>"


def _head(title):
    return ["<!DOCTYPE html>", "<html><head><meta charset=\"utf-8\">", f"<title>{html.escape(title)}</title>",
            STYLE, MARK_IMAGES, "</head><body>", f"<h1>{html.escape(title)}</h1>"]


def index_html(figure_names, summary_markdown, title="rollbench results"):
    """The page: the findings, one table of contents, the figures, then the rest of the summary."""
    findings, rest = split_summary(summary_markdown)
    shown = inline_figures(summary_markdown)
    every = [n for n in figure_names if all_methods(n)]
    figures = ordered_figures([n for n in figure_names if n not in shown and not all_methods(n)])
    sections = [line[3:] for line in rest.splitlines() if line.startswith("## ")]
    contents = "".join(f"<li><a href=\"#{slug(h)}\">{inline(h)}</a></li>" for h in ["Figures"] + sections)
    parts = _head(title)
    # the findings' figures right after its lines, before its tables
    lines = findings.splitlines()
    split = next((i for i, line in enumerate(lines) if line.startswith("### ")), len(lines))
    if findings:
        parts.append(markdown_to_html("\n".join(lines[:split])))
    parts += [_figure(n) for n in figures if n.startswith(FINDINGS_FIGURES)]
    if lines[split:]:
        parts.append(markdown_to_html("\n".join(lines[split:])))
    parts += ["<h2 id=\"contents\">Contents</h2>", f"<ul>{contents}</ul>", "<h2 id=\"figures\">Figures</h2>"]
    parts += [_figure(n) for n in figures if not n.startswith(FINDINGS_FIGURES)]
    if every:
        parts.append(f"<p>Every method's work–precision chart, one per scene ({len(every)}): "
                     f"<a href=\"{ALL_METHODS_PAGE}\">{ALL_METHODS_PAGE}</a>.</p>")
    parts += [markdown_to_html(rest), "</body></html>"]
    return "\n".join(parts) + "\n"


def all_methods_html(figure_names, title="rollbench results: every method"):
    """all-methods.html: the every-method charts of figure_names, each with its caption, and a way back."""
    names = [n for n in figure_names if all_methods(n)]
    parts = _head(title) + ["<p><a href=\"index.html\">index.html</a> has the answer and the best of each "
                            "family; here is every method's curve, one chart per scene.</p>"]
    parts += [_figure(n) for n in names] + ["</body></html>"]
    return "\n".join(parts) + "\n"
