"""analysis/safe_files.py: bounded, typed reads and the path rule for writes, and the tools that use them
(plot.py's write_all, compare.py --out, the peers' write_peer_file). The ownership tests plant another user's
(uid 65534's) links in a sticky world-writable folder; they need root to chown."""
import contextlib
import io
import json
import os
import stat
import tempfile
import threading
import unittest

from analysis import compare, plot
from analysis import report as rp
from analysis import safe_files as sf
from analysis.peers import peer_file
from tests.analysis import synthetic as syn

NOBODY = 65534
AS_ROOT = os.geteuid() == 0


def write(path, data):
    with open(path, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def read(path):
    with open(path, "rb") as f:
        return f.read()


def finishes(call, seconds=5.0):
    """(returned or raised, value or exception) of call, or fails when it has not returned within seconds."""
    outcome = []

    def run():
        try:
            outcome.append(("returned", call()))
        except BaseException as e:  # noqa: B902 (handed to the test)
            outcome.append(("raised", e))
    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(seconds)
    if not outcome:
        raise AssertionError(f"still running after {seconds} s")
    return outcome[0]


class Reads(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def refused(self, path, what="report", limit=sf.REPORT_LIMIT):
        kind, value = finishes(lambda: sf.read_text(path, what, limit))
        self.assertEqual(kind, "raised", value)
        self.assertIsInstance(value, sf.InputFileError)
        return str(value)

    def test_a_fifo_is_refused_at_once(self):
        fifo = os.path.join(self.dir, "report.json")
        os.mkfifo(fifo)
        self.assertEqual(self.refused(fifo), f"'{fifo}' is a FIFO; inputs are read only from regular files")
        kind, e = finishes(lambda: rp.load(fifo))  # the analysis's loader: exit 2 with this, never a hang
        self.assertIsInstance(e, rp.ReportError)
        self.assertEqual(str(e), f"'{fifo}' is a FIFO; inputs are read only from regular files")

    def test_a_device_and_a_folder_are_refused(self):
        self.assertEqual(self.refused("/dev/zero"),
                         "'/dev/zero' is a character device; inputs are read only from regular files")
        self.assertEqual(self.refused(self.dir), f"'{self.dir}' is a folder; inputs are read only from regular files")

    def test_an_oversize_sparse_file_is_refused_before_reading(self):
        big = os.path.join(self.dir, "big.json")
        with open(big, "wb") as f:
            f.truncate(2_150_000_000)  # sparse: nothing on disk, 2.15 GB by its size
        self.assertEqual(self.refused(big), f"'{big}' is 2.15 GB; a report is at most 1 GiB")
        with self.assertRaises(rp.ReportError) as e:
            rp.load(big)
        self.assertEqual(str(e.exception), f"'{big}' is 2.15 GB; a report is at most 1 GiB")

    def test_the_limit_is_inclusive(self):
        path = os.path.join(self.dir, "x.txt")
        write(path, "x" * 1001)
        self.assertEqual(sf.read_text(path, "scene file", 1001), "x" * 1001)
        self.assertEqual(self.refused(path, "scene file", 1000), f"'{path}' is 1001 bytes; a scene file is at most "
                                                                 "1000 bytes")
        self.assertEqual(self.refused(path, "scene file", 512), f"'{path}' is 1 kB; a scene file is at most 512 bytes")

    def test_text_that_is_not_utf8_names_the_byte(self):
        path = os.path.join(self.dir, "report.json")
        write(path, b'{"name": "\xff"}')
        self.assertEqual(self.refused(path), f"'{path}' is not UTF-8 (byte 0xff at offset 10); a report is UTF-8 text")
        with self.assertRaises(rp.ReportError) as e:
            rp.load(path)
        self.assertEqual(str(e.exception), f"'{path}' is not UTF-8 (byte 0xff at offset 10); a report is UTF-8 text")

    def test_a_path_that_is_not_utf8_is_shown_escaped(self):
        raw = os.fsencode(self.dir) + b"/\xff\x1b[31m.json"
        shown = f"'{self.dir}/\\xff\\x1b[31m.json'"
        for path in (raw, os.fsdecode(raw)):  # bytes, and str with a surrogate escape
            with self.subTest(path=path):
                self.assertEqual(self.refused(path), f"cannot read the report {shown} (No such file or directory)")
        write(raw, b"\xfe")
        self.assertEqual(self.refused(os.fsdecode(raw)),
                         f"{shown} is not UTF-8 (byte 0xfe at offset 0); a report is UTF-8 text")

    def test_a_regular_file_is_read_whole(self):
        path = os.path.join(self.dir, "r.json")
        write(path, '{"é": 1}')
        self.assertEqual(sf.read_text(path, "report"), '{"é": 1}')
        self.assertEqual(sf.read_bytes(path, "report"), '{"é": 1}'.encode())


class Writes(unittest.TestCase):
    """The path rule as any user: the caller's links are followed; a link as the last component is replaced."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_missing_folders_are_made_and_no_temporary_is_left(self):
        path = os.path.join(self.dir, "a", "b", "out.md")
        self.assertEqual(sf.write_file(path, "text", create_folders=True), path)
        self.assertEqual(read(path), b"text")
        self.assertEqual(sf.write_file(path, b"new"), path)
        self.assertEqual(os.listdir(os.path.dirname(path)), ["out.md"])
        with self.assertRaises(sf.OutputFileError) as e:
            sf.write_file(os.path.join(self.dir, "c", "out.md"), "text")
        self.assertEqual(str(e.exception), f"cannot write into '{self.dir}/c': the folder '{self.dir}/c' does not "
                                           "exist")

    def test_a_link_as_the_last_component_is_replaced_not_followed(self):
        victim = os.path.join(self.dir, "victim.md")
        write(victim, "victim")
        link = os.path.join(self.dir, "out.md")
        os.symlink(victim, link)
        sf.write_file(link, "new")
        self.assertEqual(read(victim), b"victim")
        self.assertFalse(os.path.islink(link))
        self.assertEqual(read(link), b"new")

    def test_the_callers_link_in_a_folder_component_is_followed(self):
        target = os.path.join(self.dir, "target")
        os.mkdir(target)
        os.symlink("target", os.path.join(self.dir, "link"))
        sf.write_file(os.path.join(self.dir, "link", "sub", "x.md"), "x", create_folders=True)
        self.assertEqual(read(os.path.join(target, "sub", "x.md")), b"x")

    def test_a_fifo_a_folder_a_device_or_a_stream_as_the_target_is_refused(self):
        fifo = os.path.join(self.dir, "fifo.md")
        os.mkfifo(fifo)
        os.mkdir(os.path.join(self.dir, "folder.md"))
        os.symlink("/dev/null", os.path.join(self.dir, "null.md"))
        with tempfile.TemporaryFile(dir=self.dir) as f:
            # as `--out /dev/stdout > x.md`: a link that leads through /proc to a regular file
            os.symlink(f"/proc/self/fd/{f.fileno()}", os.path.join(self.dir, "stdout.md"))
            expected = {"fifo.md": "exists and is a FIFO", "folder.md": "exists and is a folder",
                        "null.md": "is a symbolic link to a character device",
                        "stdout.md": "is a symbolic link to a stream of this process"}
            for name, what in expected.items():
                with self.subTest(name=name):
                    path = os.path.join(self.dir, name)
                    kind, e = finishes(lambda: sf.write_file(path, "x"))
                    self.assertIsInstance(e, sf.OutputFileError)
                    self.assertEqual(str(e), f"'{path}' {what}; outputs are written only to regular files")
        self.assertTrue(stat.S_ISFIFO(os.lstat(fifo).st_mode))
        self.assertEqual(os.readlink(os.path.join(self.dir, "null.md")), "/dev/null")

    def test_a_name_is_one_component(self):
        with sf.OutputFolder(self.dir) as out:
            for name in ("a/b", "..", ".", ""):
                with self.subTest(name=name), self.assertRaises(sf.OutputFileError):
                    out.write_bytes(name, b"x")

    def test_a_figure_is_saved_through_the_folder(self):
        from analysis.figures import new_figure
        fig = new_figure(2, 2)
        with sf.OutputFolder(os.path.join(self.dir, "plots")) as out:
            path = out.write_figure("f.png", fig)
        self.assertEqual(read(path)[:8], b"\x89PNG\r\n\x1a\n")


@unittest.skipUnless(AS_ROOT, "needs root: the planted links belong to uid 65534")
class PlantedLinks(unittest.TestCase):
    """A sticky world-writable folder S (as /tmp); in it nobody's folder S/nob with nobody's link S/nob/link to a
    folder of root's, and nobody's link S/link to the same. Root writes through neither; the victim is untouched."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        base = self.tmp.name
        self.victim = os.path.join(base, "victim")
        os.mkdir(self.victim)
        self.victim_file = os.path.join(self.victim, "report.json")
        write(self.victim_file, "root's")
        self.shared = os.path.join(base, "shared")
        os.mkdir(self.shared)
        os.chmod(self.shared, 0o1777)
        nob = os.path.join(self.shared, "nob")
        os.mkdir(nob)
        os.chown(nob, NOBODY, NOBODY)
        self.link = os.path.join(nob, "link")
        self.shared_link = os.path.join(self.shared, "link")
        for link in (self.link, self.shared_link):
            os.symlink(self.victim, link)
            os.lchown(link, NOBODY, NOBODY)

    def tearDown(self):
        self.tmp.cleanup()

    def assert_victim_untouched(self):
        self.assertEqual(os.listdir(self.victim), ["report.json"])
        self.assertEqual(read(self.victim_file), b"root's")

    def refusal(self, link, path):
        return (f"cannot write into '{path}': '{link}' is a symbolic link owned by uid {NOBODY} in a folder owned "
                f"by uid {os.lstat(os.path.dirname(link)).st_uid}; not followed (an output's path follows only links "
                "of its writer, uid 0, or of root: docs/bad-input.md)")

    def test_write_file_through_either_link_is_refused(self):
        for link in (self.link, self.shared_link):
            with self.subTest(link=link):
                with self.assertRaises(sf.OutputFileError) as e:
                    sf.write_file(os.path.join(link, "report.json"), "planted")
                self.assertEqual(str(e.exception), self.refusal(link, link))
                with self.assertRaises(sf.OutputFileError) as e:
                    sf.write_file(os.path.join(link, "new", "report.json"), "planted", create_folders=True)
                self.assertEqual(str(e.exception), self.refusal(link, os.path.join(link, "new")))
        self.assert_victim_untouched()

    def test_plot_write_all_through_the_link_is_refused(self):
        out = os.path.join(self.link, "plots")
        with self.assertRaises(sf.OutputFileError) as e:
            plot.write_all({"schema": rp.SCHEMA, "runs": []}, out, log=lambda _: None)
        self.assertEqual(str(e.exception), self.refusal(self.link, out))
        self.assert_victim_untouched()

    def test_compare_out_through_the_link_is_refused_with_exit_2(self):
        paths = []
        for name in ("a.json", "b.json"):
            paths.append(os.path.join(self.tmp.name, name))
            write(paths[-1], json.dumps(syn.minimal_report()))
        out = os.path.join(self.link, "report.json")
        stderr = io.StringIO()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(stderr):
            status = compare.main([*paths, "--out", out])
        self.assertEqual(status, 2)
        self.assertEqual(stderr.getvalue(), f"error: {self.refusal(self.link, self.link)}\n")
        self.assert_victim_untouched()

    def test_write_peer_file_through_the_link_is_refused(self):
        with self.assertRaises(sf.OutputFileError) as e:
            peer_file.write_peer_file(self.link, "scipy", {}, "lib.so", 1, 1.0, 0.0, "", [], [])
        self.assertEqual(str(e.exception), self.refusal(self.link, self.link))
        self.assert_victim_untouched()

    def test_links_planted_in_an_existing_output_folder_are_replaced_not_followed(self):
        out = os.path.join(self.shared, "plots")  # nobody's output folder, in which root draws
        os.mkdir(out)
        os.chown(out, NOBODY, NOBODY)
        for name in ("summary.md", "index.html"):
            os.symlink(self.victim_file, os.path.join(out, name))
            os.lchown(os.path.join(out, name), NOBODY, NOBODY)
        written = plot.write_all({"schema": rp.SCHEMA, "runs": []}, out, log=lambda _: None)
        self.assertEqual(written, [os.path.join(out, "summary.md"), os.path.join(out, "index.html")])
        for path in written:
            self.assertFalse(os.path.islink(path))
            self.assertEqual(os.stat(path).st_uid, 0)
        self.assertTrue(read(os.path.join(out, "index.html")).startswith(b"<!DOCTYPE html>"))
        self.assert_victim_untouched()

    def test_root_follows_its_own_link_in_the_shared_folder(self):
        own = os.path.join(self.shared, "own")
        os.symlink(self.victim, own)
        sf.write_file(os.path.join(own, "new.md"), "root's own")
        self.assertEqual(read(os.path.join(self.victim, "new.md")), b"root's own")


if __name__ == "__main__":
    unittest.main()
