"""The byte-level pieces of editing: reading a file's layout, rendering, splicing."""

from __future__ import annotations

import codecs

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree

from sensorkit.base.errors import EditRefused, InputError
from sensorkit.edit.diff import unified_diff
from sensorkit.edit.layout import read_layout
from sensorkit.edit.render import format_number, render_block, xacro_literal, xml_attr
from sensorkit.edit.splice import _splice


def layout_of(text: str, encoding: str = "utf-8", bom: bytes = b""):  # type: ignore[no-untyped-def]
    return read_layout(bom + text.encode(encoding), "test.urdf")


# --------------------------------------------------------------------------- layout


def test_closing_tag_found_past_lookalikes() -> None:
    text = (
        '<?xml version="1.0"?>\n'
        "<!DOCTYPE robot [ <!-- </robot> --> <!ATTLIST x y CDATA '</robot>'> ]>\n"
        '<robot name="r"><!-- </robot> -->\n'
        '  <link name="a"><![CDATA[</robot>]]></link>\n'
        '  <joint name="j>"/>\n'
        "</robot>\n<!-- </robot> -->\n"
    )
    lay = layout_of(text)
    assert text[lay.root_end_at :].startswith("</robot>\n<!--")
    assert text[lay.root_start_at : lay.root_start_end] == '<robot name="r">'
    assert lay.root_name == "robot"


@pytest.mark.parametrize(
    ("indent", "unit"),
    [("  ", "  "), ("    ", "    "), ("\t", "\t"), ("", "  ")],
)
def test_indentation(indent: str, unit: str) -> None:
    text = (
        f'<robot name="r">\n{indent}<link name="a">\n{indent}{unit}<visual/>\n'
        f"{indent}</link>\n</robot>\n"
    )
    lay = layout_of(text)
    assert (lay.indent, lay.unit) == (indent, unit)


def test_indentation_majority_wins_and_unit_from_grandchildren() -> None:
    text = '<robot name="r">\n  <a/>\n  <b>\n      <c/>\n  </b>\n <d/>\n</robot>'
    lay = layout_of(text)
    assert lay.indent == "  " and lay.unit == "    "


@pytest.mark.parametrize(("nl", "expect"), [("\n", "\n"), ("\r\n", "\r\n"), ("\r", "\r")])
def test_newline_style(nl: str, expect: str) -> None:
    text = nl.join(['<robot name="r">', '  <link name="a"/>', "</robot>", ""])
    assert layout_of(text).newline == expect


def test_encodings() -> None:
    text = '<?xml version="1.0" encoding="ISO-8859-1"?>\n<robot name="é">\n</robot>\n'
    lay = read_layout(text.encode("latin-1"), "x")
    assert lay.encoding == "iso8859-1" and lay.bom == b""
    assert lay.byte_offset(lay.root_end_at) == text.encode("latin-1").index(b"</robot>")
    assert lay.encode("\u2713") == b"&#10003;"  # not in Latin-1: a character reference

    lay = layout_of('<robot name="r">\n</robot>\n', bom=codecs.BOM_UTF8)
    assert lay.bom == codecs.BOM_UTF8 and lay.byte_offset(0) == 3

    data = '<robot name="r">\n</robot>\n'.encode("utf-16")
    lay = read_layout(data, "x")
    assert lay.encoding == "utf-16-le" and data[lay.byte_offset(lay.root_end_at) :].decode(
        "utf-16-le"
    ).startswith("</robot>")


def test_unusable_files() -> None:
    with pytest.raises(EditRefused, match="empty"):
        layout_of('<robot name="r"/>\n')
    with pytest.raises(InputError, match="UTF-32"):
        read_layout('<robot name="r"></robot>'.encode("utf-32"), "x")
    with pytest.raises(InputError, match="not valid"):
        read_layout(b'<robot name="\xff"></robot>', "x")
    with pytest.raises(InputError, match="unknown encoding"):
        read_layout(b'<?xml version="1.0" encoding="klingon"?><robot></robot>', "x")


def test_line_helpers() -> None:
    text = '<robot name="r">\n  <a/>\n\n  </robot>\n'
    lay = layout_of(text)
    start = lay.line_start_before(lay.root_end_at)
    assert start == text.index("  </robot>")
    assert lay.previous_line_blank(start)
    lay = layout_of('<robot name="r">\n  <a/></robot>')
    assert lay.line_start_before(lay.root_end_at) is None


# --------------------------------------------------------------------------- rendering


def test_format_number_round_trips() -> None:
    assert [format_number(v) for v in (0.0, -0.0, 1.0, 0.2, -3.5, 1e-5, 640)] == [
        "0", "0", "1", "0.2", "-3.5", "1e-05", "640",
    ]  # fmt: skip
    with pytest.raises(Exception, match="finite"):
        format_number(float("nan"))


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_format_number_is_exact(value: float) -> None:
    assert float(format_number(value)) == value


def test_escapes() -> None:
    assert xml_attr('a"<&>\n') == "a&quot;&lt;&amp;&gt;&#10;"
    assert xacro_literal("a${b}$(c)$d") == "a$${b}$$(c)$d"


def test_render_block_uses_the_files_style() -> None:
    lay = layout_of('<robot name="r">\r\n\t<a>\r\n\t\t<b/>\r\n\t</a>\r\n</robot>\r\n')
    block = render_block(
        [(0, "<x>"), (1, "<y/>"), (0, "</x>")], lay, at_line_start=True, blank_before=True
    )
    assert block == "\r\n\t<x>\r\n\t\t<y/>\r\n\t</x>\r\n"
    block = render_block([(0, "<x/>")], lay, at_line_start=False, blank_before=True)
    assert block == "\r\n\t<x/>\r\n"


def test_unified_diff_marks_missing_final_newline() -> None:
    diff = unified_diff("a\nb", "a\nb\nc", "a/f", "b/f")
    assert "\\ No newline at end of file" in diff


# --------------------------------------------------------------------------- splicing (property)

NEWLINES = st.sampled_from(["\n", "\r\n"])
INDENTS = st.sampled_from(["", "  ", "    ", "\t"])
COMMENT_TEXT = st.sampled_from(["", " </robot> ", " note ", " a > b ", " <link name='x'/> "])


@st.composite
def robot_text(draw: st.DrawFn) -> str:
    nl = draw(NEWLINES)
    ind = draw(INDENTS)
    head = draw(
        st.sampled_from(
            ["", '<?xml version="1.0"?>' + nl, "<?xml version='1.0' encoding='utf-8'?>" + nl]
        )
    )
    pieces: list[str] = []
    for i in range(draw(st.integers(0, 5))):
        kind = draw(st.sampled_from(["link", "comment", "cdata", "blank", "inline"]))
        if kind == "link":
            pieces.append(f'{ind}<link name="l{i}">{nl}{ind}{ind}<visual/>{nl}{ind}</link>{nl}')
        elif kind == "comment":
            pieces.append(f"{ind}<!--{draw(COMMENT_TEXT)}-->{nl}")
        elif kind == "cdata":
            pieces.append(f"{ind}<gazebo><![CDATA[ </robot> ]]></gazebo>{nl}")
        elif kind == "blank":
            pieces.append(nl)
        else:
            pieces.append(f'{ind}<link name="m{i}"/><!--{draw(COMMENT_TEXT)}-->{nl}')
    close = draw(st.sampled_from(["</robot>", "</robot >", ind + "</robot>"]))
    inline_close = draw(st.booleans())
    body = "".join(pieces)
    if inline_close and body.endswith(nl):
        body = body[: -len(nl)]
    tail = draw(st.sampled_from(["", nl, nl + "<!-- </robot> -->" + nl]))
    return f'{head}<robot name="r">{nl}{body}{close}{tail}'


@settings(max_examples=60, deadline=None)
@given(robot_text(), st.booleans())
def test_splice_lands_before_the_closing_tag(text: str, bom: bool) -> None:
    data = (codecs.BOM_UTF8 if bom else b"") + text.encode()
    etree.fromstring(data)  # the generator makes well-formed files
    lay = read_layout(data, "x")
    at = lay.line_start_before(lay.root_end_at)
    at = lay.root_end_at if at is None else at

    assert _splice(data, lay, "", at, None) == data  # a no-op edit is byte-identical

    marker = "<!-- sensorkit marker -->"
    new = _splice(data, lay, marker, at, ' xmlns:xacro="http://www.ros.org/wiki/xacro"')
    root = etree.fromstring(new)
    last = root[-1]
    assert isinstance(last, etree._Comment) and last.text == " sensorkit marker "
    assert root.nsmap.get("xacro") == "http://www.ros.org/wiki/xacro"
    it = iter(new)
    assert all(any(c == d for d in it) for c in data)  # every original byte, in order


TAIL_ITEMS = st.sampled_from(["", "\n", "<!-- </robot> -->", "<?pi </robot> ?>", "<?pi x?>\n", " "])


@st.composite
def styled_robot(draw: st.DrawFn) -> str:
    """Files whose indentation varies per element, with comments and PIs in between."""
    nl = draw(NEWLINES)
    ws = st.sampled_from(["", " ", "  ", "    ", "\t", " \t"])
    parts = [draw(st.sampled_from(["", '<?xml version="1.0"?>' + nl, "<!-- head -->" + nl]))]
    parts.append('<robot name="r"' + draw(st.sampled_from(["", nl + "  x='1'"])) + ">")
    for i in range(draw(st.integers(0, 6))):
        lead = draw(st.sampled_from([nl, "", nl + nl, " "])) + draw(ws)
        kind = draw(st.sampled_from(["leaf", "nested", "comment", "pi", "text"]))
        if kind == "leaf":
            parts.append(f'{lead}<link name="l{i}"/>')
        elif kind == "nested":
            inner = "".join(
                draw(st.sampled_from([nl, "", " "])) + draw(ws) + f"<c{j}/>"
                for j in range(draw(st.integers(0, 3)))
            )
            parts.append(f'{lead}<link name="n{i}">{inner}{draw(st.sampled_from([nl, ""]))}</link>')
        elif kind == "comment":
            parts.append(f"{lead}<!-- c{i} -->")
        elif kind == "pi":
            parts.append(f"{lead}<?p {i}?>")
        else:
            parts.append(f"{lead}&amp;")
    parts.append(
        draw(st.sampled_from([nl, "", "  "])) + "</robot" + draw(st.sampled_from(["", " "])) + ">"
    )
    parts.extend(draw(TAIL_ITEMS) for _ in range(draw(st.integers(0, 3))))
    return "".join(parts)


@settings(max_examples=200, deadline=None)
@given(st.one_of(robot_text(), styled_robot()), st.booleans())
def test_layout_from_the_tree_is_the_full_scan(text: str, bom: bool) -> None:
    """``read_layout`` given the parsed root reads the tree, not every tag: same answer."""
    from sensorkit.loading.document import strict_parser

    data = (codecs.BOM_UTF8 if bom else b"") + text.encode()
    root = etree.fromstring(data, strict_parser())
    assert read_layout(data, "x", root) == read_layout(data, "x")
