# SPDX-License-Identifier: BSD-3-Clause
"""Every ParaView proxy of the plugin is documented: a short_help and long text per
proxy, a <Documentation> for every visible property, the menu category "Deformable
Surface" and each visible non-input property in a PropertyGroup (filters; readers are
reached through File > Open instead)."""
import glob
import os
import sys
import xml.etree.ElementTree as ET

xml_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "xml")
files = sorted(glob.glob(os.path.join(xml_dir, "*.xml")))
failures = []
proxies = 0
for path in files:
    root = ET.parse(path).getroot()
    for proxy in root.iter("SourceProxy"):
        proxies += 1
        name = proxy.get("name")
        doc = proxy.find("Documentation")
        if doc is None or not doc.get("short_help") or len((doc.text or "").strip()) < 40:
            failures.append("%s: proxy %s lacks a short_help and a real description" % (path, name))
        is_reader = proxy.find("Hints/ReaderFactory") is not None
        menu = proxy.find("Hints/ShowInMenu")
        if not is_reader and (menu is None or menu.get("category") != "Deformable Surface"):
            failures.append("%s: proxy %s is not in the 'Deformable Surface' menu" % (path, name))
        grouped = set()
        for group in proxy.iter("PropertyGroup"):
            for p in group.iter("Property"):
                grouped.add(p.get("name"))
        for prop in proxy:
            if not prop.tag.endswith("Property"):
                continue
            if prop.get("panel_visibility") == "never":
                continue
            pname = prop.get("name")
            pdoc = prop.find("Documentation")
            if pdoc is None or len((pdoc.text or "").strip()) < 15:
                failures.append("%s: %s.%s has no real <Documentation>" % (path, name, pname))
            # Information-only properties (TimestepValues) are never shown in the panel.
            if (prop.tag != "InputProperty" and not is_reader and pname not in grouped
                    and prop.get("panel_visibility") != "advanced" and prop.get("information_only") != "1"):
                failures.append("%s: %s.%s is in no PropertyGroup" % (path, name, pname))

print("checked %d proxies in %d files" % (proxies, len(files)))
for f in failures:
    print("FAILED:", f)
if proxies == 0 or failures:
    sys.exit(1)
