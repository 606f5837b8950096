"""index.html: every figure and summary.md in one page.

summary.md is rendered here (headings, lists, tables, paragraphs, `code`
and **bold**: what summary.py writes); everything is HTML-escaped. A small
script marks each image data-state="loaded" or "broken", so a headless
browser can check that the page shows every figure.
"""
import html
import re

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
</style>"""


def inline(text):
    text = html.escape(text, quote=False)
    text = re.sub(r"`([^`]+)`", r"<code>\1</code>", text)
    return re.sub(r"\*\*([^*]+)\*\*", r"<strong>\1</strong>", text)


def _cells(line):
    # split on '|' that is not escaped as '\|'
    parts = re.split(r"(?<!\\)\|", line.strip().strip("|"))
    return [p.strip().replace("\\|", "|") for p in parts]


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
            out.append("<ul>" + "".join(f"<li>{inline(b)}</li>" for b in bullets) + "</ul>")
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
            out.append(f"<h{level}>{inline(heading.group(2))}</h{level}>")
        elif line.startswith("|"):
            table.append(line)
        elif line.startswith("- "):
            bullets.append(line[2:])
        elif not line.strip():
            flush()
        else:
            paragraph.append(line.strip())
    flush()
    return "\n".join(out)


def index_html(figure_names, summary_markdown, title="rollbench results"):
    """The page: the figures (relative links, in the given order), then the summary."""
    parts = ["<!DOCTYPE html>", "<html><head><meta charset=\"utf-8\">", f"<title>{html.escape(title)}</title>",
             STYLE, MARK_IMAGES, "</head><body>", f"<h1>{html.escape(title)}</h1>", "<h2>Figures</h2>"]
    for name in figure_names:
        link = html.escape(name, quote=True)
        parts.append(f"<figure><img src=\"{link}\" alt=\"{link}\"><figcaption>{html.escape(name)}</figcaption>"
                     "</figure>")
    parts += ["<h2>Summary (summary.md)</h2>", markdown_to_html(summary_markdown), "</body></html>"]
    return "\n".join(parts) + "\n"
