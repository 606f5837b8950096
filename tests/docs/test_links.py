"""Every relative link in README.md and docs/*.md resolves inside the
repository: the file exists and, for #anchor, the heading does. The README
links only inside the repository; docs/ may also cite http(s) pages."""
import glob
import os
import re
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# [text](target) and ![alt](target), target up to a space or ')'
LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^\s{0,3}#{1,6}\s+(.*?)\s*#*\s*$")


def prose_lines(text):
    """The lines outside fenced code blocks, with inline code removed."""
    inside = False
    for line in text.splitlines():
        if FENCE.match(line):
            inside = not inside
            continue
        if not inside:
            yield re.sub(r"`[^`]*`", "", line)


def anchors(text):
    """GitHub's anchors for the headings of a Markdown text."""
    seen = {}
    out = set()
    inside = False
    for line in text.splitlines():
        if FENCE.match(line):
            inside = not inside
            continue
        m = None if inside else HEADING.match(line)
        if not m:
            continue
        title = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", m.group(1)).replace("`", "")
        slug = re.sub(r"[^\w\- ]", "", title.lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        out.add(slug if n == 0 else f"{slug}-{n}")
    return out


def problems(path, root=ROOT, external_allowed=False):
    """What is wrong with the links of one Markdown file, one sentence each."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    name = os.path.relpath(path, root)
    found = []
    for line in prose_lines(text):
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):
                if not (external_allowed and re.match(r"^https?://", target)):
                    found.append(f"{name}: '{target}' leaves the repository")
                continue
            file_part, _, anchor = target.partition("#")
            resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            if os.path.relpath(resolved, root).startswith(os.pardir):
                found.append(f"{name}: '{target}' leaves the repository")
                continue
            if not os.path.exists(resolved):
                found.append(f"{name}: '{target}': no such file {os.path.relpath(resolved, root)}")
                continue
            if anchor and resolved.endswith(".md"):
                with open(resolved, encoding="utf-8") as f:
                    if anchor not in anchors(f.read()):
                        found.append(f"{name}: '{target}': no heading with the anchor #{anchor}")
    return found


class ProjectLinks(unittest.TestCase):
    def test_readme_links_resolve_inside_the_repository(self):
        self.assertEqual(problems(os.path.join(ROOT, "README.md")), [])

    def test_docs_links_resolve(self):
        docs = sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")))
        self.assertGreaterEqual(len(docs), 4, "docs/ holds model.md, formats.md, design.md, bad-input.md")
        for doc in docs:
            self.assertEqual(problems(doc, external_allowed=True), [], doc)


class Checker(unittest.TestCase):
    """The check itself finds each kind of bad link."""

    def test_each_kind_of_bad_link_is_named(self):
        with tempfile.TemporaryDirectory() as root:
            os.mkdir(os.path.join(root, "docs"))
            with open(os.path.join(root, "docs", "a.md"), "w") as f:
                f.write("# A title, with `code`\n## Same\n## Same\n")
            page = os.path.join(root, "README.md")
            with open(page, "w") as f:
                f.write(
                    "# Top\n"
                    "[ok](docs/a.md) [ok](docs/a.md#a-title-with-code) [ok](docs/a.md#same-1) [ok](#top)\n"
                    "[out](../shared/MODEL.md) [gone](docs/b.md) [anchor](docs/a.md#nothing)\n"
                    "[web](https://example.org/x)\n"
                    "```\n[in code](../ignored.md)\n```\n"
                    "`[inline](../ignored.md)`\n"
                )
            self.assertEqual(
                problems(page, root=root),
                [
                    "README.md: '../shared/MODEL.md' leaves the repository",
                    "README.md: 'docs/b.md': no such file docs/b.md",
                    "README.md: 'docs/a.md#nothing': no heading with the anchor #nothing",
                    "README.md: 'https://example.org/x' leaves the repository",
                ],
            )
            self.assertEqual(problems(page, root=root, external_allowed=True)[-1:],
                             ["README.md: 'docs/a.md#nothing': no heading with the anchor #nothing"])


if __name__ == "__main__":
    unittest.main()
