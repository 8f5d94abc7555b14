"""Measured surface profiles from files: plain two-column text, or every SurfaceTopography format.

* :func:`read_columns` / :func:`read_text` — a plain reader for two-column text or CSV files
  (instrument exports with a header block, such as a Dektak CSV). Units come from the column
  header (``Lateral um``, ``Raw Micrometer``, ``x [nm]``, ``# x_um h_um`` …) or from the
  ``unit`` argument. Needs only numpy.
* :func:`write_text` — the inverse: a profile as ``x [um], h [um]`` text (exact round trip).
* :func:`read_topography` / :func:`read_map` — any file the ContactEngineering
  `SurfaceTopography <https://github.com/ContactEngineering/SurfaceTopography>`_ package reads
  (``read_topography``: x3p, opd, sdf, datx, di, ibw, plux, WSxM, Dektak, …): a line scan, or
  one row of a 2-D map. Optional: ``pip install 'gecko_agents[topography]'``; imported only
  when called.
* :func:`load` — the plain reader for text files, SurfaceTopography for everything else.

Every reader converts to µm and returns a :class:`gecko_agents.floor.Profile` through
:func:`gecko_agents.floor.from_profile` (detrended, uniformly resampled), except the raw
:func:`read_columns` and :func:`read_map`.
"""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np

from gecko_agents.floor import LENGTH_UNITS, Profile, from_profile, length_factor

__all__ = [
    "read_columns",
    "read_text",
    "write_text",
    "read_topography",
    "read_map",
    "load",
    "TEXT_SUFFIXES",
    "uniform_grid",
    "printed_resolution",
]

TEXT_SUFFIXES = (".csv", ".txt", ".dat", ".asc", ".xy", ".tsv")
"""File name endings :func:`load` reads with the plain text reader."""

_INSTALL = "pip install 'gecko_agents[topography]'"
# Unit words in a column header: longest first so 'micrometer' wins over 'm'.
_UNIT_WORDS = sorted(LENGTH_UNITS, key=len, reverse=True)
_UNIT_RE = re.compile(
    r"(?<![a-zµμå])(" + "|".join(re.escape(u) for u in _UNIT_WORDS) + r")(?![a-zµμå])",
    re.IGNORECASE,
)


def _fields(line: str) -> list[str]:
    return [f for f in re.split(r"[\s,;]+", line.strip().strip(",;")) if f != ""]


def _is_data(line: str, columns: tuple[int, int]) -> bool:
    """Whether the ``columns`` of a line are numbers (NaN and inf count: refused later)."""
    f = _fields(line)
    if len(f) <= max(columns):
        return False
    try:
        [float(f[c]) for c in columns]
    except ValueError:
        return False
    return True


def _is_comment(line: str) -> bool:
    """A comment line (``#`` or ``%``) or an empty one."""
    text = line.strip()
    return not text or text[0] in "#%"


def _data_above(lines: list[str], i: int, columns: tuple[int, int]) -> bool:
    """Whether the nearest line above line ``i`` that is not a comment or empty is data."""
    j = i - 1
    while j >= 0 and _is_comment(lines[j]):
        j -= 1
    return j >= 0 and _is_data(lines[j], columns)


def _header_units(header: str, columns: tuple[int, int]) -> tuple[str | None, str | None]:
    """Units of the two columns named in a header line, or None where none is given."""
    text = header.lstrip("#% ").strip()
    names = [n for n in re.split(r"\s*[,;\t]\s*", text) if n != ""]
    if len(names) <= max(columns):  # whitespace-separated names
        names = text.split()
    units = []
    for c in columns:
        m = _UNIT_RE.findall(names[c].replace("_", " ")) if c < len(names) else []
        units.append(m[-1] if m else None)
    return units[0], units[1]


def read_columns(
    path,
    *,
    columns: tuple[int, int] = (0, 1),
    unit: str | None = None,
    height_unit: str | None = None,
) -> tuple[np.ndarray, np.ndarray, str, str]:
    """The raw two columns of a text/CSV profile file, as written: (x, h, x_unit, h_unit).

    The data block is the run of lines, up to the end of the file, whose ``columns`` are
    numbers (separators: comma, semicolon, tab or spaces; trailing empty fields allowed);
    comment (``#``, ``%``) and empty lines inside it are read past, any other line inside it
    is refused naming its line number (the rows above it would otherwise be dropped); the
    line just above it is read as the column header. Units come from that header (``Lateral
    um``, ``Raw Micrometer``, ``x [nm]``, ``h_um`` …) or from ``unit`` / ``height_unit``; a
    header unit that contradicts the argument is refused. The file is decoded as UTF-8, else
    latin-1 (instrument exports often write µ as byte 0xB5).

    Parameters
    ----------
    path : the file.
    columns : indices of the x and height columns (0-based).
    unit : length unit of x (and of h unless ``height_unit``), if the header gives none.
    height_unit : length unit of h, if the header gives none.
    """
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as err:
        raise ValueError(f"cannot read profile file {str(path)!r}: {err}") from err
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    block = _whole_block(text, columns)
    header, data = block if block is not None else _line_block(path, text, columns)
    if len(data) < 2:
        raise ValueError(
            f"{str(path)!r} is not a two-column profile: found {len(data)} "
            f"numeric rows in columns {columns} at its end"
        )
    hx, hh = _header_units(header, columns) if header else (None, None)
    arg_x = unit
    arg_h = height_unit if height_unit is not None else unit
    x_unit = _pick_unit(path, "unit", hx, arg_x)
    h_unit = _pick_unit(path, "height_unit", hh, arg_h, fallback=x_unit)
    return data[:, 0], data[:, 1], x_unit, h_unit


_ODD_BREAKS = "\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029"  # str.splitlines breaks lines there too
_HEAD_LINES = 10_000  # header lines looked through for the first data line
_CHUNK = 1 << 24  # characters parsed at a time (~16 MB of text, ~0.6 M rows)


def _whole_block(text: str, columns: tuple[int, int]) -> tuple[str, np.ndarray] | None:
    """(header line, rows of the ``columns``) when every line from the first data line to the
    end is numbers (blank lines allowed), parsed by ``numpy.loadtxt`` in chunks: a 10⁷-row
    file in seconds, not the minutes of reading line by line. None when any line there is a
    comment, junk or ends oddly: :func:`_line_block` then reads it (same result, or an error
    naming the line)."""
    text = text.replace("\r\n", "\n").replace("\r", "\n")  # as str.splitlines reads them
    if any(c in text for c in _ODD_BREAKS):
        return None
    pos, header = 0, ""
    for _ in range(_HEAD_LINES):
        nl = text.find("\n", pos)
        line = text[pos : nl if nl >= 0 else len(text)]
        if _is_data(line, columns):
            break
        header = line if line.strip() else header
        if nl < 0:
            return None
        pos = nl + 1
    else:
        return None
    parts = []
    while pos < len(text):
        nl = text.find("\n", min(pos + _CHUNK, len(text)))
        stop = len(text) if nl < 0 else nl + 1
        chunk = text[pos:stop]
        pos = stop
        if "#" in chunk or "%" in chunk:  # comments: read line by line
            return None
        if not chunk.strip():
            continue
        try:
            parts.append(
                np.loadtxt(
                    io.StringIO(chunk.replace(",", " ").replace(";", " ")),
                    usecols=columns,
                    comments=None,
                    ndmin=2,
                    dtype=float,
                )
            )
        except ValueError:
            return None
    return header, np.concatenate(parts) if parts else np.zeros((0, 2))


def _line_block(path: Path, text: str, columns: tuple[int, int]) -> tuple[str, np.ndarray]:
    """(header line, rows of the ``columns``) of the data block at the end of ``text``, line
    by line (see :func:`read_columns`); a non-numeric line inside it is refused naming its
    line number."""
    lines = text.splitlines()
    end = len(lines)
    while end > 0 and not lines[end - 1].strip():
        end -= 1
    start, skipped = end, []
    while start > 0:
        line = lines[start - 1]
        if _is_data(line, columns):
            start -= 1
        elif _is_comment(line) and _data_above(lines, start - 1, columns):
            skipped.append(start - 1)  # a comment inside the data block is read past
            start -= 1
        else:
            break
    if start > 0 and _data_above(lines, start - 1, columns):
        raise ValueError(
            f"{str(path)!r} line {start}: {lines[start - 1].strip()[:60]!r} is not numbers in "
            f"columns {columns}, and numbers stand above it: the data block is interrupted "
            "(remove or comment out the line with '#'; the rows above it would be dropped)"
        )
    header = next((ln for ln in reversed(lines[:start]) if ln.strip()), "")
    skip = set(skipped)
    rows = [ln for i, ln in enumerate(lines[start:end], start) if i not in skip]
    data = np.array([[float(_fields(ln)[c]) for c in columns] for ln in rows]).reshape(-1, 2)
    return header, data


def _pick_unit(
    path: Path,
    name: str,
    from_header: str | None,
    from_arg: str | None,
    fallback: str | None = None,
) -> str:
    if from_header is not None and from_arg is not None:
        if length_factor(from_header) != length_factor(from_arg, name):
            raise ValueError(
                f"{name} = {from_arg!r} contradicts the unit {from_header!r} in "
                f"the header of {str(path)!r}"
            )
    unit = from_header or from_arg or fallback
    if unit is None:
        raise ValueError(
            f"no length unit in the header of {str(path)!r}: pass {name}='um' (or 'nm', 'mm', …)"
        )
    length_factor(unit, name)
    return unit


def read_text(
    path,
    *,
    columns: tuple[int, int] = (0, 1),
    unit: str | None = None,
    height_unit: str | None = None,
    **kwargs,
) -> Profile:
    """A floor profile from a two-column text/CSV file (:func:`read_columns`), a uniform scan
    printed with rounded positions read on its true grid (:func:`uniform_grid`), converted to
    µm, detrended and resampled by :func:`gecko_agents.floor.from_profile` (``kwargs``:
    ``spacing``, ``detrend``, ``x_range``)."""
    x, h, ux, uh = read_columns(path, columns=columns, unit=unit, height_unit=height_unit)
    return from_profile(
        uniform_grid(x), h, unit=ux, height_unit=uh, source=Path(path).name, **kwargs
    )


def printed_resolution(x: np.ndarray, max_decimals: int = 9) -> float:
    """The finest decimal step ``x`` was printed with: 10⁻ᵈ for the fewest decimals d that
    write every value (to 1e-6 of the step), e.g. 0.1 for a column of 0.0, 0.2, 0.3, …"""
    x = np.asarray(x, float)
    sample = x[:1000]  # consecutive values: a d that fails on them fails on x, skipped fast

    def whole(v, d):
        scaled = v * 10.0**d
        return np.all(np.abs(scaled - np.round(scaled)) <= 1e-6 * np.maximum(1.0, np.abs(scaled)))

    for d in range(max_decimals + 1):
        if whole(sample, d) and whole(x, d):
            return 10.0**-d
    return 0.0


def uniform_grid(x: np.ndarray) -> np.ndarray:
    """``x`` put back on its true uniform grid if it is a uniform grid printed rounded.

    Instruments sample uniformly but may print positions coarser than their spacing (a Dektak
    export writes 0.1 µm for a 0.15625 µm sampling, so its steps read 0.1 or 0.2 µm); read as
    written, the heights would be placed up to half a print step off and every resampled slope
    distorted. ``x`` is taken as the grid x₀ + k·Δ, Δ = (x_last − x₀)/(n − 1), when every value
    lies within one print step (:func:`printed_resolution`) of it — the most rounding and the
    rounding of the end points can move a value — and a non-uniform scan, whose points stray
    further, is returned unchanged.
    """
    x = np.asarray(x, float)
    if x.size < 3:
        return x
    grid = x[0] + (x[-1] - x[0]) * np.arange(x.size) / (x.size - 1)
    step = printed_resolution(x)
    if step > 0 and np.max(np.abs(x - grid)) <= step * (1 + 1e-9):
        return grid
    return x


def write_text(path, profile: Profile) -> Path:
    """Write a profile as text: a ``x [um], h [um]`` header, then one ``x, h`` row per vertex
    (17 significant digits, so :func:`read_columns` gives back the same floats)."""
    path = Path(path)
    rows = np.column_stack([np.asarray(profile.x, float), np.asarray(profile.y, float)])
    with path.open("w", encoding="utf-8") as f:
        if profile.source:
            f.write(f"# {profile.source}\n")
        f.write("x [um], h [um]\n")
        np.savetxt(f, rows, fmt="%.17g", delimiter=", ")
    return path


def _surface_topography():
    try:
        import SurfaceTopography
    except ImportError as err:
        raise ImportError(
            f"reading this file needs the optional SurfaceTopography package: {_INSTALL}"
        ) from err
    return SurfaceTopography


def _open(path, channel: int | None):
    st = _surface_topography()
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"cannot read {str(path)!r}: no such file")
    try:
        reader = st.open_topography(str(path))
        kw = {} if channel is None else {"channel_index": int(channel)}
        topo = reader.topography(**kw)
    except Exception as err:  # SurfaceTopography raises many kinds for unreadable files
        raise ValueError(
            f"SurfaceTopography cannot read {str(path)!r}: {type(err).__name__}: {err}"
        ) from err
    if topo.unit is None:
        raise ValueError(f"{str(path)!r} gives no length unit; SurfaceTopography needs one")
    return topo, length_factor(topo.unit, f"unit of {path.name}")


def read_map(path, *, channel: int | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A 2-D topography map through SurfaceTopography, in µm, as stored (no detrending):
    (x [µm] shape (nx,), y [µm] shape (ny,), heights [µm] shape (nx, ny), heights[i, j] at
    (x_i, y_j)). ``channel``: the data channel (default: the file's default)."""
    topo, f = _open(path, channel)
    if topo.dim != 2:
        raise ValueError(f"{str(path)!r} is a line scan, not a 2-D map: use read_topography")
    xg, yg = topo.positions()
    h = np.ma.filled(np.ma.asarray(topo.heights(), dtype=float), np.nan)
    return np.asarray(xg)[:, 0] * f, np.asarray(yg)[0, :] * f, h * f


def read_topography(
    path, *, row: int | None = None, channel: int | None = None, **kwargs
) -> Profile:
    """A floor profile from any file SurfaceTopography's ``read_topography`` reads.

    A line scan is used whole (a uniform scan printed with rounded positions on its true grid,
    :func:`uniform_grid`); of a 2-D map the profile along x at the y index ``row`` is
    taken (required for maps; heights[:, row] of :func:`read_map`). Heights and positions are
    converted from the file's unit to µm and passed to
    :func:`gecko_agents.floor.from_profile` (``kwargs``: ``spacing``, ``detrend``,
    ``x_range``). Needs ``pip install 'gecko_agents[topography]'``.
    """
    path = Path(path)
    topo, f = _open(path, channel)
    if topo.dim == 1:
        if row is not None:
            raise ValueError(f"row = {row!r} given but {str(path)!r} is a line scan")
        x, h = topo.positions_and_heights()
        x = uniform_grid(np.asarray(x, float) * f) / f  # a Dektak file prints x rounded
        h = np.ma.filled(np.ma.asarray(h, dtype=float), np.nan)
        name = path.name
    else:
        nx, ny = topo.nb_grid_pts
        if (
            row is None
            or isinstance(row, bool)
            or not isinstance(row, int | np.integer)
            or not 0 <= row < ny
        ):
            raise ValueError(
                f"row = {row!r}: {str(path)!r} is a {nx} × {ny} map; choose the "
                f"row (y index) in [0, {ny - 1}]"
            )
        xg, _ = topo.positions()
        x = np.asarray(xg)[:, 0]
        h = np.ma.filled(np.ma.asarray(topo.heights(), dtype=float), np.nan)[:, row]
        name = f"{path.name} row {row}"
    return from_profile(np.asarray(x, float) * f, h * f, unit="um", source=name, **kwargs)


def load(path, **kwargs) -> Profile:
    """Any profile file: the plain reader for text files (:data:`TEXT_SUFFIXES`), otherwise
    SurfaceTopography (:func:`read_topography`; ``row`` for maps)."""
    if (
        Path(path).suffix.lower() in TEXT_SUFFIXES
        and "row" not in kwargs
        and "channel" not in kwargs
    ):
        return read_text(path, **kwargs)
    return read_topography(path, **kwargs)
