"""Presentation: the small HTML tables that results show in a notebook (``_repr_html_``)."""

from __future__ import annotations


def table(title: str, rows: list[tuple[str, str]]) -> str:
    """An HTML table of ``rows`` (label, value) under ``title``, every string escaped."""
    # lazy: html and its table of named entities, only a notebook's display needs them
    import html

    body = "".join(
        f"<tr><th style='text-align:left'>{html.escape(k)}</th><td>{html.escape(v)}</td></tr>"
        for k, v in rows
    )
    return f"<table><caption>{html.escape(title)}</caption>{body}</table>"
