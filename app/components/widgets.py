"""The page's small building blocks (trame + Vuetify 3), used by every component's UI section:
compact selects, icon buttons, lists of alerts and of buttons bound to a state list, chart
elements, colour swatches, and the classes presenter mode reads.

A binding is written as trame takes it: a tuple ``("expression",)`` is evaluated in the page, a
plain string is a literal.
"""

from __future__ import annotations

from trame.widgets import html
from trame.widgets import vuetify3 as v3

from .. import lazy_charts

#: Class of the blocks that presenter mode hides (app/lessons/widgets.py styles it).
HIDE = "rt-hide-in-presenter"


def chart_classes(chart: str) -> tuple[str]:
    """The ``classes`` binding of a chart's wrapper: highlighted when it is the lesson's chart
    (in presenter mode without a lesson, the contact-angle chart is the one shown)."""
    return (
        f"(lesson_chart || (presenter ? 'contact_angle' : '')) === '{chart}' "
        "? 'mb-2 rt-chart rt-lesson-chart' : 'mb-2 rt-chart'",
    )


def own_update():
    """A wrapper whose content is re-rendered on its own (Vuetify's ``VDefaultsProvider``, which
    adds no element): the page tracks the state its content reads as this wrapper's, so a change
    of that state re-renders the content only, not the section around it. For what changes with
    every played frame."""
    return v3.VDefaultsProvider()


def select(label: str, model: str, items, **extra) -> None:
    """A compact select bound to state ``model``; ``items``: a state name or a JS list literal."""
    v3.VSelect(
        label=label,
        v_model=(model,),
        items=(items,),
        density="compact",
        hide_details=True,
        **extra,
    )


def choices(pairs) -> str:
    """A JS list literal of ``{title, value}`` items from ``(value, title)`` pairs (for
    :func:`select`)."""
    return (
        "[" + ", ".join(f"{{title: '{title}', value: '{value}'}}" for value, title in pairs) + "]"
    )


def button(label: str, element_id: str, click, disabled: str, **extra) -> None:
    """A small button, off while the JS condition ``disabled`` holds."""
    v3.VBtn(label, id=element_id, click=click, disabled=(disabled,), size="small", **extra)


def icon_button(icon: str, click, element_id: str, size: str = "small", **extra) -> None:
    """A flat icon button (``click``: a controller action or a JS statement)."""
    v3.VBtn(icon=icon, click=click, size=size, variant="text", id=element_id, **extra)


def alert(alert_type: str, *children, classes: str = "my-1 text-caption", **extra):
    """A compact tonal alert of ``alert_type`` (warning, error, info); a context for its content."""
    return v3.VAlert(
        *children, type=alert_type, density="compact", variant="tonal", classes=classes, **extra
    )


def alert_list(items: str, alert_type: str, element_id: str, **extra) -> None:
    """``div#<element_id>`` with one compact alert per entry of the state list ``items`` (shown
    only while the list is not empty)."""
    with html.Div(v_if=f"{items}.length", id=element_id, **extra):
        alert(alert_type, "{{ entry }}", v_for=f"entry in {items}", key="entry")


def checkbox(label: str, model: str, **extra) -> None:
    """A compact checkbox bound to the state flag ``model``."""
    v3.VCheckbox(label=label, v_model=(model,), density="compact", hide_details=True, **extra)


def button_list(items: str, item: str, id_prefix: str, click, selected: str, **extra) -> None:
    """One small button per entry ``item`` of the state list ``items``: labelled by
    ``item.label`` (or ``extra["label"]``), id ``<id_prefix><key>``; ``selected``: the JS
    condition of the entry on show (drawn flat)."""
    label = extra.pop("label", f"{{{{ {item}.label }}}}")
    key = extra.pop("key", f"{item}.name")
    idle = extra.pop("idle", "outlined")
    v3.VBtn(
        label,
        v_for=f"{item} in {items}",
        key=key,
        id=(f"'{id_prefix}' + {key}",),
        click=click,
        size="x-small",
        variant=(f"{selected} ? 'flat' : '{idle}'",),
        color="primary",
        classes="ma-1 text-none",
        **extra,
    )


def chart(
    element_id: str, key: str, help_text: str, height="250px", overlay: str | None = None
) -> None:
    """``div#<element_id>``: the plotly figure of state ``key`` (loaded lazily, see
    :mod:`app.lazy_charts`) and its help text; highlighted when a lesson points at it.
    ``height``: a CSS height, or a tuple binding of a JS expression in pixels; ``overlay``: the
    state key of what marks the current frame on a chart that follows the time (merged by the
    page)."""
    style = (
        (f"`height: ${{{height[0]}}}px; width: 100%;`",)
        if isinstance(height, tuple)
        else f"height: {height}; width: 100%;"
    )
    with html.Div(id=element_id, classes=chart_classes(key.removeprefix("chart_"))):
        with own_update():  # a new figure re-renders the chart, not the column around it
            lazy_charts.ChartFigure(key, overlay, display_mode_bar=False, style=style)
        caption(help_text)


def caption(text: str) -> None:
    """A line of help in small grey type."""
    html.Div(text, classes="text-caption text-medium-emphasis px-2")


def swatch(colour_expr: str) -> None:
    """A small square in the colour of the JS expression ``colour_expr``."""
    html.Span(
        style=(
            "{display: 'inline-block', width: '12px', height: '12px', borderRadius: '2px', "
            f"verticalAlign: 'middle', background: {colour_expr}}}",
        ),
    )
