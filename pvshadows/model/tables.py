"""Small HTML tables for Jupyter's rich display of reports and measurements."""

from __future__ import annotations

from collections.abc import Sequence
from html import escape


def html_table(caption: str, header: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """Return an HTML table, every cell escaped.

    Parameters
    ----------
    caption : str
        Text above the table.
    header : sequence of str
        Column titles.
    rows : sequence of sequence
        Cells, row by row (``None`` shows as an empty cell).

    Returns
    -------
    str
        The ``<table>`` element.

    Examples
    --------
    >>> from pvshadows.model.tables import html_table
    >>> table = html_table("a & b", ["x"], [[1], [None]])
    >>> "<caption>a &amp; b</caption>" in table, "<td>1</td>" in table, "<td></td>" in table
    (True, True, True)
    """
    head = "".join(f"<th>{escape(str(title))}</th>" for title in header)
    body = "".join(
        "<tr>" + "".join(f"<td>{'' if c is None else escape(str(c))}</td>" for c in row) + "</tr>"
        for row in rows
    )
    return (
        f"<table><caption>{escape(caption)}</caption><thead><tr>{head}</tr></thead>"
        f"<tbody>{body}</tbody></table>"
    )
