"""Read YAML into plain Python data plus the line of every key and item.

PyYAML's composer gives nodes with marks; we convert them ourselves so that
(1) every value keeps its line for error messages, (2) alias bombs and absurd
nesting are stopped by a node budget instead of exhausting memory, and
(3) duplicate keys are reported instead of silently overwritten.
"""

from __future__ import annotations

import codecs
import errno
import os
import stat
from dataclasses import dataclass, field

import yaml

from robosolve.errors import InputError, InputIssue

MAX_FILE_BYTES = 1_000_000
MAX_NODES = 100_000
MAX_DEPTH = 40

Path = tuple  # of str keys and int indices


@dataclass
class Source:
    """Parsed YAML: `data` plus the 1-based line of each path."""

    data: object
    lines: dict = field(default_factory=dict)
    file: str = "<input>"

    def line(self, path: Path) -> int:
        """Line of `path`, or of its nearest ancestor that has one."""
        p = tuple(path)
        while p:
            if p in self.lines:
                return self.lines[p]
            p = p[:-1]
        return self.lines.get((), 1)


class YamlProblem(Exception):
    """A file that is not YAML robosolve reads, at `line`; `path`: the value it is about, when the
    file could be read that far (the key of a nesting too deep, a number too long, a scalar's tag)."""

    def __init__(self, line: int, message: str, path: Path = ()):
        self.line = line
        self.message = message
        self.path = path
        super().__init__(message)


def _holder(path: Path) -> Path:
    """The section of the file that holds a value nested too deep (`parameters` for
    parameters.L1[0][0]…): the same whether the converter or the scan of `_deep_line` finds it."""
    return tuple(path)[:1]


class _Converter:
    def __init__(self):
        self.nodes = 0
        self.lines: dict = {}
        self.duplicates: list[tuple[int, Path, str]] = []
        self._scalar_loader = yaml.SafeLoader("")

    def convert(self, node, path: Path, depth: int):
        self.nodes += 1
        if self.nodes > MAX_NODES:
            raise YamlProblem(node.start_mark.line + 1,
                              f"the file expands to more than {MAX_NODES} values "
                              "(aliases repeated too often?)")
        if depth > MAX_DEPTH:
            raise YamlProblem(node.start_mark.line + 1,
                              f"nesting deeper than {MAX_DEPTH} levels", _holder(path))
        if isinstance(node, yaml.MappingNode):
            out: dict = {}
            for key_node, value_node in node.value:
                if not isinstance(key_node, yaml.ScalarNode):
                    raise YamlProblem(key_node.start_mark.line + 1,
                                      "a key must be a plain name, not a list or mapping", path)
                if key_node.tag == "tag:yaml.org,2002:merge":
                    raise YamlProblem(key_node.start_mark.line + 1,
                                      "merge keys ('<<') are not supported", path)
                key = self._scalar(key_node, path)
                if isinstance(key, float) or key is None or isinstance(key, bool):
                    key = key_node.value
                key = str(key) if not isinstance(key, str) else key
                kpath = path + (key,)
                if key in out:
                    self.duplicates.append((key_node.start_mark.line + 1, kpath, key))
                self.lines[kpath] = key_node.start_mark.line + 1
                out[key] = self.convert(value_node, kpath, depth + 1)
            return out
        if isinstance(node, yaml.SequenceNode):
            out_list = []
            for i, item in enumerate(node.value):
                ipath = path + (i,)
                self.lines[ipath] = item.start_mark.line + 1
                out_list.append(self.convert(item, ipath, depth + 1))
            return out_list
        return self._scalar(node, path)

    def _scalar(self, node, path: Path = ()):
        try:
            return self._scalar_loader.construct_object(node, deep=True)
        except Exception as exc:  # e.g. an integer with too many digits
            line = node.start_mark.line + 1
            digits = sum(c.isdigit() for c in node.value)
            if isinstance(exc, ValueError) and "digits" in str(exc):
                raise YamlProblem(line, f"number too long ({digits} digits; at most 4300)", path) from None
            if isinstance(exc, yaml.constructor.ConstructorError) and "constructor for the tag" in str(exc):
                tag = node.tag.replace("tag:yaml.org,2002:", "!!")
                raise YamlProblem(line, f"invalid value {node.value[:40]!r}: the YAML tag '{tag}' is not one "
                                        "robosolve reads (write the value without it)", path) from None
            # PyYAML's own text quotes the file again over three lines ("in <unicode string>, line
            # 4…"): its first sentence only, the line is given already
            said = getattr(exc, "problem", None) or str(exc)
            raise YamlProblem(line, f"invalid value {node.value[:40]!r}: {' '.join(said.split())}", path) from None


def path_problem(text: str, written: str | None = None) -> str | None:
    """Why the system cannot even look up the path `text`, in words: a name longer than it
    allows, a loop of symbolic links, no permission (None: it can, or the path does not exist,
    or a part of it is a file: the caller says what it expected there). The message quotes
    `written` (the path as the user wrote it) when given."""
    shown = _shown(text if written is None else written)
    try:
        os.stat(text)
    except FileNotFoundError:
        return None
    except OSError as exc:
        if exc.errno == errno.ENAMETOOLONG:
            longest = max(len(part.encode("utf-8", "surrogateescape")) for part in text.split(os.sep))
            limit = os.pathconf(os.sep, "PC_NAME_MAX") if hasattr(os, "pathconf") else 255
            if longest > limit:
                return (f"'{shown}': a name in this path has {longest} characters; "
                        f"the system allows at most {limit}")
            return f"'{shown}': the path is longer than the system allows"
        if exc.errno == errno.ELOOP:
            return f"'{shown}': the path goes round a loop of symbolic links"
        if exc.errno == errno.ENOTDIR:  # a file used as a folder: the commands say it
            return None
        if exc.errno == errno.EACCES:
            return f"'{shown}': permission denied"
        return f"'{shown}': {exc.strerror or exc}"
    except ValueError:              # a NUL character (YAML's "\0")
        return f"'{shown}': a path cannot hold a NUL character"
    return None


def _sibling_hint(name: str) -> str:
    """' (did you mean 'arm.yaml'?)' for a missing file beside YAML files of a close name (the
    names compared without their suffix: every one ends in .yaml)."""
    from robosolve.load.expressions import closest

    folder, base = os.path.split(name)
    try:
        near = sorted(f for f in os.listdir(folder or ".") if f.lower().endswith((".yaml", ".yml")))
    except OSError:
        return ""
    stems = {os.path.splitext(f)[0]: f for f in near}
    meant = closest(os.path.splitext(base)[0], stems)
    return f" (did you mean '{os.path.join(folder, stems[meant])}'?)" if meant is not None else ""


def _shown(text: str, width: int = 60) -> str:
    text = text.replace("\0", "\\0")
    return text if len(text) <= width else text[:width // 2] + "…" + text[-width // 2:]


def read_input_bytes(file, limit: int = MAX_FILE_BYTES, line: int = 0, what: str = "the file") -> bytes:
    """At most `limit` bytes of the regular file `file`: an InputError (at `line`) for a device,
    a pipe, a folder or a longer file. Never reads more than `limit` + 1 bytes, so that
    `/dev/zero` or a huge file cannot fill the memory; a FIFO is opened without waiting."""
    name = str(file)

    def refuse(message):
        return InputError([InputIssue(name, line, "", message)])

    try:
        fd = os.open(file, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except FileNotFoundError as exc:
        raise refuse(f"cannot read {what}: {exc.strerror or exc}{_sibling_hint(name)}") from None
    except OSError as exc:
        raise refuse(f"cannot read {what}: {exc.strerror or exc}") from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            kind = "a folder" if stat.S_ISDIR(mode) else "a device, pipe or socket"
            raise refuse(f"{what} is {kind}, not a regular file")
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(fd, limit + 1 - size)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as exc:
        raise refuse(f"cannot read {what}: {exc.strerror or exc}") from None
    finally:
        os.close(fd)
    if size > limit:
        raise refuse(f"{what} is larger than {limit} bytes")
    return b"".join(chunks)


def decode_utf8(raw: bytes, file, what: str = "the file", bom: bool = True) -> str:
    """`raw` as UTF-8 text (a leading byte-order mark dropped when `bom`), or an InputError at
    the line of the first byte that is not UTF-8."""
    if bom and raw.startswith(codecs.BOM_UTF8):
        raw = raw[len(codecs.BOM_UTF8):]
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        column = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
        byte = raw[exc.start:exc.start + 1].hex()
        if raw.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):   # Notepad's "Unicode"
            message = f"{what} is UTF-16 text, not UTF-8 (save it as UTF-8)"
            line = 1
        else:
            message = f"{what} is not UTF-8 text: byte 0x{byte} at column {column} (save it as UTF-8)"
        raise InputError([InputIssue(str(file), line, "", message)]) from None


def read_text_file(file, line: int = 0, what: str = "the file", limit: int = MAX_FILE_BYTES) -> str:
    """The UTF-8 text of `file` (at most `limit` bytes), or an InputError saying why it cannot
    be read: at `line` when the file cannot be opened, at the line of a bad byte."""
    return decode_utf8(read_input_bytes(file, limit=limit, line=line, what=what), file, what)


def read_table_file(file, line: int = 0, what: str = "the table", limit: int = MAX_FILE_BYTES) -> str:
    """The text of a CSV table a spreadsheet saved (a roster, variants.csv): UTF-8, with or
    without a byte-order mark, or UTF-16 with its byte-order mark (Excel's "Unicode text",
    tab-separated), else an InputError as `read_text_file` gives."""
    raw = read_input_bytes(file, limit=limit, line=line, what=what)
    if raw.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        try:
            return raw.decode("utf-16").removeprefix("\ufeff")
        except UnicodeDecodeError:
            raise InputError([InputIssue(str(file), 1, "", f"{what} starts as UTF-16 text but is not "
                                         "(save it as UTF-8)")]) from None
    return decode_utf8(raw, file, what)


_OPENING = (yaml.FlowSequenceStartToken, yaml.FlowMappingStartToken, yaml.BlockMappingStartToken,
            yaml.BlockSequenceStartToken)
_CLOSING = (yaml.FlowSequenceEndToken, yaml.FlowMappingEndToken, yaml.BlockEndToken)


def _too_deep(text: str) -> YamlProblem:
    line, section = _deep_line(text)
    return YamlProblem(line, f"nesting deeper than {MAX_DEPTH} levels", section)


def _deep_line(text: str) -> tuple[int, Path]:
    """The line where the nesting first goes deeper than MAX_DEPTH levels (PyYAML's scanner is
    not recursive: it reads any depth). The top-level mapping opens a level of the scan but is
    depth 0 of the converter: the line must be the converter's, which says it when composing
    does not run out of stack first (a larger recursion limit, a deeper caller)."""
    depth, key, section = -1, False, ()
    try:
        for token in yaml.scan(text, Loader=yaml.SafeLoader):
            if isinstance(token, _OPENING):
                depth += 1
                if depth > MAX_DEPTH:
                    return token.start_mark.line + 1, section
            elif isinstance(token, _CLOSING):
                depth -= 1
            elif isinstance(token, yaml.ScalarToken) and key and depth == 0:
                section = (token.value,)        # a key of the top mapping: the section below it
            key = isinstance(token, yaml.KeyToken)
    except (yaml.YAMLError, RecursionError):
        pass
    return 1, section


def _character_problem(text: str, exc) -> YamlProblem:
    """A character YAML does not allow, at its line and column, named in words."""
    pos = exc.position if isinstance(exc.position, int) else 0
    line = text.count("\n", 0, pos) + 1
    column = pos - (text.rfind("\n", 0, pos) + 1) + 1
    code = exc.character if isinstance(exc.character, int) else ord(text[pos]) if pos < len(text) else 0
    what = "a NUL character (byte 0)" if code == 0 else f"the control character U+{code:04X}"
    return YamlProblem(line, f"{what} at column {column}: YAML does not allow it in a file "
                       "(remove it; was the file saved as UTF-16 or binary?)")


def parse_yaml(text: str, file: str = "<input>", limit: int = MAX_FILE_BYTES) -> tuple[Source, list[tuple[int, Path, str]]]:
    """Parse YAML text of at most `limit` bytes. Raises YamlProblem for syntax errors and
    resource limits.

    Returns the Source and the duplicate keys found (line, path, key).
    """
    if len(text.encode("utf-8", "replace")) > limit:
        raise YamlProblem(1, f"file larger than {limit} bytes")
    try:
        documents = list(yaml.compose_all(text, Loader=yaml.SafeLoader))
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark else 1
        what = exc.problem or exc.context or "syntax error"
        lines = text.splitlines()
        near = lines[max(line - 2, 0):line + 1]
        if "\t" in text and (any("\t" in ln for ln in near) or "tab" in what):
            what += " (a tab character: indent with spaces, YAML does not allow tabs)"
        raise YamlProblem(line, f"YAML syntax error: {what}") from None
    except yaml.reader.ReaderError as exc:      # a character YAML does not allow (NUL, ...)
        raise _character_problem(text, exc) from None
    except yaml.YAMLError as exc:
        raise YamlProblem(1, f"YAML error: {exc}") from None
    except RecursionError:
        raise _too_deep(text) from None
    if len(documents) > 1:
        raise YamlProblem(documents[1].start_mark.line + 1,
                          "more than one YAML document in the file ('---')")
    if not documents or documents[0] is None:
        raise YamlProblem(1, "the file is empty (expected a mapping with `robosolve: 1`)")
    conv = _Converter()
    try:
        data = conv.convert(documents[0], (), 0)
    except RecursionError:
        raise _too_deep(text) from None
    conv.lines[()] = documents[0].start_mark.line + 1
    return Source(data, conv.lines, file), conv.duplicates
