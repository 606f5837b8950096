"""Every file the analysis and the peers read or write goes through here (docs/bad-input.md, "The analysis and
the peers: reads and the path rule").

Reads: read_bytes/read_text open without blocking (a FIFO never hangs), accept only a regular file, refuse one over
its kind's limit before reading a byte, read at most the limit, and decode UTF-8 strictly; InputFileError names the
path and what is wrong.

Writes: an output folder is opened component by component from / or the working folder, each with
O_DIRECTORY | O_NOFOLLOW, so that a symbolic link is followed only where this module says so: when the caller
(the effective uid) or root owns it, its target walked by the same rule. A file is written as a temporary made
with O_EXCL in that folder and renamed over the target, which must be missing, a regular file or a link to one or
to nothing (the link itself is replaced, its target untouched); a link to a device, a FIFO, a folder or a stream
of the process (/dev/stdout) is refused. OutputFileError names what was refused.
"""
import errno
import os
import stat

KiB, MiB, GiB = 1 << 10, 1 << 20, 1 << 30
# the largest input of each kind read, far above what rollbench writes (the same as the C++ side,
# problems/input_file.hpp, where a kind is in both)
REPORT_LIMIT = 1 * GiB      # a report or shard (rollbench run's default preset writes a few MB)
PEER_FILE_LIMIT = 64 * MiB  # a peer file (peers.json) or a peer's result
SCENE_LIMIT = 1 * MiB       # a scene file
TRAJECTORY_LIMIT = 256 * MiB  # a trajectory CSV
TEXT_LIMIT = 64 * MiB       # anything else read whole: a benchmark file, a README
LONGEST_SHOWN_PATH = 4096   # PATH_MAX
MAX_LINKS = 40              # links followed in one path, as the kernel's MAXSYMLINKS
_FOLDER_FLAGS = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC


class InputFileError(ValueError):
    """An input that cannot be read, or is not a regular file of UTF-8 within its limit; the message names it."""


class OutputFileError(ValueError):
    """An output that cannot be written, or would be written through a link not followed; the message names it."""


def shown(path):
    """A path as messages show it, quoted: control characters, quotes, backslashes and bytes outside ASCII as \\xNN
    (a path that is not UTF-8, bytes or str with surrogate escapes, never raises)."""
    raw = os.fsencode(path)
    text = "".join(chr(c) if 0x20 <= c < 0x7f and c not in b"\\'" else f"\\x{c:02x}" for c in raw[:LONGEST_SHOWN_PATH])
    return "'" + text + ("..." if len(raw) > LONGEST_SHOWN_PATH else "") + "'"


def size_in_words(size):
    """'812 bytes', '1.07 GB' (three digits, powers of 1000), as the C++ side."""
    if size < 1000:
        return f"{size} byte" + ("" if size == 1 else "s")
    value, unit = size / 1000, 0
    units = ("kB", "MB", "GB", "TB", "PB", "EB")
    while value >= 999.5 and unit + 1 < len(units):
        value, unit = value / 1000, unit + 1
    return f"{value:.3g} {units[unit]}"


def limit_in_words(size):
    """'1 GiB', '64 MiB' when a whole number of them, else as size_in_words."""
    for unit, name in ((GiB, "GiB"), (MiB, "MiB"), (KiB, "KiB")):
        if size >= unit and size % unit == 0:
            return f"{size // unit} {name}"
    return size_in_words(size)


def kind_of(mode):
    """What a file is, in words: "a FIFO", "a folder"."""
    kinds = ((stat.S_ISREG, "a file"), (stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO"),
             (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"),
             (stat.S_ISLNK, "a symbolic link"))
    for test, name in kinds:
        if test(mode):
            return name
    return "not a regular file"


def _article(what):
    return "an" if what[:1] in "aeiou" else "a"


# -- reads ---------------------------------------------------------------------------------------------------------

def read_bytes(path, what="input", limit=TEXT_LIMIT):
    """The bytes of the regular file at path (links followed, as a path the user typed should), at most limit of
    them; InputFileError otherwise. what names the kind in messages ("report", "peer file")."""
    limit_words = limit_in_words(limit)
    limit_text = f"; {_article(what)} {what} is at most {limit_words}"
    try:
        # O_NONBLOCK: a FIFO without a writer opens at once (and is refused below); O_NOCTTY: a terminal never
        # becomes ours. A device is refused by its stat before it is opened at all.
        before = os.stat(path)
        if not stat.S_ISREG(before.st_mode):
            raise InputFileError(f"{shown(path)} is {kind_of(before.st_mode)}; inputs are read only from regular files")
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC)
    except OSError as e:
        raise InputFileError(f"cannot read the {what} {shown(path)} ({e.strerror})") from None
    try:
        st = os.fstat(fd)  # what was opened, whatever the path names now
        if not stat.S_ISREG(st.st_mode):
            raise InputFileError(f"{shown(path)} is {kind_of(st.st_mode)}; inputs are read only from regular files")
        if st.st_size > limit:
            size_words = size_in_words(st.st_size)
            if size_words == limit_words:  # a size just past the limit, in bytes: not "1 kB; at most 1 kB"
                size_words, limit_text = f"{st.st_size} bytes", f"; {_article(what)} {what} is at most {limit} bytes"
            raise InputFileError(f"{shown(path)} is {size_words}{limit_text}")
        chunks, have = [], 0
        while have <= limit:  # one byte past the limit tells a file that grew
            chunk = os.read(fd, min(limit + 1 - have, max(st.st_size + 1 - have, 64 * KiB)))
            if not chunk:
                break
            chunks.append(chunk)
            have += len(chunk)
        if have > limit:
            raise InputFileError(f"{shown(path)} grew past {limit_words} while it was read{limit_text}")
        return b"".join(chunks)
    except OSError as e:
        raise InputFileError(f"cannot read the {what} {shown(path)} ({e.strerror})") from None
    finally:
        os.close(fd)


def read_text(path, what="input", limit=TEXT_LIMIT):
    """read_bytes decoded as UTF-8, strictly: "'PATH' is not UTF-8 (byte 0xff at offset 12)"."""
    data = read_bytes(path, what, limit)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise InputFileError(f"{shown(path)} is not UTF-8 (byte 0x{data[e.start]:02x} at offset {e.start}); "
                             f"{_article(what)} {what} is UTF-8 text") from None


# -- writes --------------------------------------------------------------------------------------------------------

def _link_followed(link):
    """Whether a link (its lstat) on an output's path is followed: owned by this process's effective uid or by root,
    since only then can no one else have pointed it elsewhere (as the C++ side, problems/safe_path.hpp). The
    kernel's protected_symlinks also follows a link whose owner owns its folder: a user's folder inside a shared
    one (S/nob in the sticky S) could then point S/nob/link at /root and have root's output land there."""
    return link.st_uid in (os.geteuid(), 0)


def _refused_link(path, where, link, folder):
    return OutputFileError(
        f"cannot write into {shown(path)}: {shown(where)} is a symbolic link owned by uid {link.st_uid} in a folder "
        f"owned by uid {folder.st_uid}; not followed (an output's path follows only links of its writer, uid "
        f"{os.geteuid()}, or of root: docs/bad-input.md)")


def _components(path):
    """(start, [component, ...]) of a path as bytes; '.' and empty components dropped."""
    raw = os.fsencode(path)
    return (b"/" if raw.startswith(b"/") else b"."), [c for c in raw.split(b"/") if c not in (b"", b".")]


def _open_dir(name, dir_fd=None):
    """A folder's descriptor, never following a link as name; O_PATH where the folder may be searched, not read."""
    try:
        return os.open(name, _FOLDER_FLAGS, dir_fd=dir_fd)
    except PermissionError:
        return os.open(name, _FOLDER_FLAGS | os.O_PATH, dir_fd=dir_fd)


def _open_folder(path, create, parent_fd=None, parent_path=None):
    """A descriptor of the folder path, opened component by component from parent_fd (whose path is parent_path),
    else from / or the working folder; missing folders made when create."""
    start, pending = _components(path)
    pending.reverse()  # a stack: a link's target is pushed onto it
    full = os.fsdecode(path) if parent_path is None else os.path.join(parent_path, os.fsdecode(path))
    if parent_fd is None or start == b"/":
        fd, where = _open_dir(start), (b"/" if start == b"/" else b"")
    else:
        fd, where = os.dup(parent_fd), os.fsencode(parent_path)
    here = where  # the path walked so far, as messages show it
    links = 0
    try:
        while pending:
            part = pending.pop()
            here = where + part if where.endswith(b"/") or not where else where + b"/" + part
            try:
                next_fd = _open_dir(part, fd)
            except FileNotFoundError:
                if not create:
                    raise OutputFileError(f"cannot write into {shown(full)}: the folder {shown(here)} does not "
                                          "exist") from None
                try:
                    os.mkdir(part, 0o777, dir_fd=fd)
                except FileExistsError:
                    pass  # made meanwhile: opened as any other below
                pending.append(part)
                continue
            except OSError as e:
                if e.errno not in (errno.ELOOP, errno.ENOTDIR):
                    raise
                st = os.stat(part, dir_fd=fd, follow_symlinks=False)
                if not stat.S_ISLNK(st.st_mode):
                    raise OutputFileError(f"cannot write into {shown(full)}: {shown(here)} is {kind_of(st.st_mode)}, "
                                          "not a folder") from None
                if not _link_followed(st):
                    raise _refused_link(full, here, st, os.fstat(fd)) from None
                links += 1
                if links > MAX_LINKS:
                    raise OutputFileError(f"cannot write into {shown(full)}: more than {MAX_LINKS} symbolic links")
                # the target is walked here too, each of its links under the same rule
                target_start, target_parts = _components(os.readlink(part, dir_fd=fd))
                pending.extend(reversed(target_parts))
                if target_start == b"/":
                    os.close(fd)
                    fd, where = _open_dir(b"/"), b"/"
                continue
            os.close(fd)
            fd, where = next_fd, here
        return fd
    except OSError as e:
        os.close(fd)
        raise OutputFileError(f"cannot write into {shown(full)}: {shown(here)} ({e.strerror})") from None
    except BaseException:
        os.close(fd)
        raise


def _check_name(name):
    raw = os.fsencode(name)
    if not raw or raw in (b".", b"..") or b"/" in raw or b"\0" in raw:
        raise OutputFileError(f"{shown(name)} is not a file name (one path component, not '.' or '..')")
    return raw


class OutputFolder:
    """An output folder opened once under the path rule; every file is written through its descriptor.

        with OutputFolder("out/plots") as out:
            out.write_text("summary.md", text)
            out.write_figure("answer.png", fig, bbox_inches="tight")
    """

    def __init__(self, path, create=True, _parent=None):
        self._fd = None
        self._fd = _open_folder(path, create, *((_parent._fd, _parent.path) if _parent else ()))
        self.path = _parent.joined(path) if _parent else os.fsdecode(path)
        self._count = 0

    def joined(self, name):
        """The path of name in this folder, as the caller gave it."""
        return os.path.join(self.path, os.fsdecode(name))

    def subfolder(self, name, create=True):
        """A folder inside this one (its own path rule from here): an OutputFolder."""
        return OutputFolder(name, create, _parent=self)

    def close(self):
        if self._fd is not None:
            try:
                os.fsync(self._fd)  # the renames made it into the folder
            except OSError:
                pass
            os.close(self._fd)
            self._fd = None

    def __enter__(self):
        return self

    def __exit__(self, *_):
        self.close()

    def __del__(self):
        if getattr(self, "_fd", None) is not None:
            os.close(self._fd)

    def _check_target(self, raw):
        """Refuses a target that is not missing, a regular file, or a link (to a regular file or to nothing)."""
        path = self.joined(os.fsdecode(raw))
        try:
            st = os.stat(raw, dir_fd=self._fd, follow_symlinks=False)
        except FileNotFoundError:
            return
        if stat.S_ISREG(st.st_mode):
            return
        if not stat.S_ISLNK(st.st_mode):
            raise OutputFileError(f"{shown(path)} exists and is {kind_of(st.st_mode)}; outputs are written only to "
                                  "regular files")
        # a link is replaced, never followed; but not one that stands for a stream or a device (/dev/stdout:
        # renaming over it would replace the system's link with a file)
        try:
            target = os.stat(raw, dir_fd=self._fd)
        except OSError:
            return  # dangling: replaced
        if not stat.S_ISREG(target.st_mode) or _leads_into_proc(os.fsencode(self.path), raw):
            what = kind_of(target.st_mode) if not stat.S_ISREG(target.st_mode) else "a stream of this process"
            raise OutputFileError(f"{shown(path)} is a symbolic link to {what}; outputs are written only to "
                                  "regular files")

    def write_bytes(self, name, data):
        """Writes data to name in this folder (temporary, fsync, rename over the old file); the path written."""
        raw = _check_name(name)
        path = self.joined(name)
        self._check_target(raw)
        self._count += 1
        temp = b"." + raw[:200] + f".tmp.{os.getpid()}.{self._count}".encode()
        try:
            fd = os.open(temp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o666,
                         dir_fd=self._fd)
        except OSError as e:
            raise OutputFileError(f"cannot write {shown(path)} ({e.strerror})") from None
        try:
            try:
                view = memoryview(data)
                while view:
                    view = view[os.write(fd, view):]
                os.fsync(fd)
            finally:
                os.close(fd)
            self._check_target(raw)  # once more just before the rename
            os.replace(temp, raw, src_dir_fd=self._fd, dst_dir_fd=self._fd)
        except OSError as e:
            _unlink_quietly(temp, self._fd)
            raise OutputFileError(f"cannot write {shown(path)} ({e.strerror})") from None
        except BaseException:
            _unlink_quietly(temp, self._fd)
            raise
        return path

    def write_text(self, name, text):
        """write_bytes of text in UTF-8 (a lone surrogate from a JSON escape written as \\udXXX)."""
        return self.write_bytes(name, text.encode("utf-8", "backslashreplace"))

    def write_figure(self, name, fig, **savefig_args):
        """A Matplotlib figure saved into memory, in the format of name's extension, then written as write_bytes."""
        import io
        buffer = io.BytesIO()
        fig.savefig(buffer, format=os.path.splitext(name)[1][1:] or "png", **savefig_args)
        return self.write_bytes(name, buffer.getvalue())


def _unlink_quietly(name, dir_fd):
    try:
        os.unlink(name, dir_fd=dir_fd)
    except OSError:
        pass


def _leads_into_proc(folder, name):
    """Whether the link name in folder leads, through links, into /proc (/dev/stdout -> /proc/self/fd/1)."""
    try:
        proc = os.stat("/proc").st_dev
    except OSError:
        return False
    path = os.path.join(folder, name)
    for _ in range(MAX_LINKS):
        try:
            st = os.lstat(path)
        except OSError:
            return False
        if st.st_dev == proc:
            return True
        if not stat.S_ISLNK(st.st_mode):
            return False
        path = os.path.join(os.path.dirname(path), os.readlink(path))
    return True


class OutputFile:
    """One output file, its folder opened and the target checked now, written later (write): an --out is refused
    before the work it would hold.

        with OutputFile(args.out) as out:
            ...
            out.write(text)
    """

    def __init__(self, path, create_folders=False):
        folder, self.name = os.path.split(os.fsdecode(path))
        if not self.name:
            raise OutputFileError(f"{shown(path)} names a folder, not a file")
        _check_name(self.name)
        self.folder = OutputFolder(folder, create_folders)
        try:
            self.folder._check_target(os.fsencode(self.name))
        except BaseException:
            self.folder.close()
            raise

    def write(self, data):
        """Writes data (bytes, or str as UTF-8); the path written."""
        if isinstance(data, str):
            return self.folder.write_text(self.name, data)
        return self.folder.write_bytes(self.name, data)

    def close(self):
        self.folder.close()

    def __enter__(self):
        return self

    def __exit__(self, *_):
        self.close()


def write_file(path, data, create_folders=False):
    """Writes data (bytes, or str as UTF-8) to path under the path rule; the path written."""
    with OutputFile(path, create_folders) as out:
        return out.write(data)


def output_folder(folder, create=True):
    """folder as an OutputFolder: itself when it is one (left open), else opened (closed on leaving)."""
    import contextlib
    if isinstance(folder, OutputFolder):
        return contextlib.nullcontext(folder)
    return OutputFolder(folder, create)
