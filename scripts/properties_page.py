#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes docs/PROPERTIES.md, the reference of every property of the plugin's proxies, from the
server-manager XML (xml/*.xml), where each property's default and documentation live: one table
per proxy, in the order of its panel groups. --check exits 1 when the page is not what the XML
gives (scripts/check_docs.sh runs it; rerun this script after changing an XML file)."""
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
PAGE = os.path.join(ROOT, "docs", "PROPERTIES.md")


def one_line(text):
    return re.sub(r"\s+", " ", (text or "").strip()).replace("|", "\\|")


def default_text(prop):
    """The default as the panel shows it: on/off, an enumeration's text, else the XML's values."""
    values = prop.get("default_values")
    if values is None:
        return "active scalars" if prop.get("command") == "SetInputArrayToProcess" else ""
    if prop.find("BooleanDomain") is not None:
        return "on" if values.strip() == "1" else "off"
    enum = prop.find("EnumerationDomain")
    if enum is not None:
        for entry in enum.findall("Entry"):
            if entry.get("value") == values.strip():
                return entry.get("text")
    return values


def groups(proxy):
    """{property name: its panel group's label}; the rest fall under 'Other'."""
    labels = {}
    for group in proxy.iter("PropertyGroup"):
        for p in group.iter("Property"):
            labels.setdefault(p.get("name"), group.get("label"))
    return labels


def proxy_section(proxy, xml_name):
    doc = proxy.find("Documentation")
    lines = ["## %s" % proxy.get("label", proxy.get("name")), "",
             "`%s` (VTK class `%s`, [xml/%s](../xml/%s)): %s" % (
                 proxy.get("name"), proxy.get("class"), xml_name, xml_name,
                 one_line(doc.get("short_help") if doc is not None else "")), ""]
    labels = groups(proxy)
    rows = []
    order = {label: i for i, label in enumerate(dict.fromkeys(labels.values()))}
    for prop in proxy:
        if not prop.tag.endswith("Property") or prop.tag == "InputProperty":
            continue
        if prop.get("information_only") == "1" or prop.get("panel_visibility") == "never":
            continue
        group = labels.get(prop.get("name"), "Other")
        name = "`%s`%s" % (prop.get("name"), " (advanced)" if prop.get("panel_visibility") == "advanced" else "")
        pdoc = prop.find("Documentation")
        rows.append((order.get(group, len(order)), group, name, default_text(prop),
                     one_line(pdoc.text if pdoc is not None else "")))
    rows.sort(key=lambda r: r[0])  # stable: the XML's order within a group
    lines += ["| group | property | default | meaning |", "|---|---|---|---|"]
    lines += ["| %s | %s | %s | %s |" % r[1:] for r in rows]
    return lines + [""]


def page():
    lines = ["# Properties", "",
             "Generated from the server-manager XML by `scripts/properties_page.py`; do not edit by "
             "hand. The XML holds each property's default and documentation (ParaView shows the same "
             "text under the panel's `?`).", ""]
    for path in sorted(glob.glob(os.path.join(ROOT, "xml", "*.xml"))):
        for proxy in ET.parse(path).getroot().iter("SourceProxy"):
            lines += proxy_section(proxy, os.path.basename(path))
    return "\n".join(lines)


def main(argv):
    text = page()
    if "--check" in argv:
        current = open(PAGE).read() if os.path.exists(PAGE) else ""
        if current != text:
            print("docs/PROPERTIES.md is not what xml/*.xml gives: run scripts/properties_page.py")
            return 1
        print("docs/PROPERTIES.md matches xml/*.xml")
        return 0
    with open(PAGE, "w") as f:
        f.write(text)
    print("wrote", PAGE)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
