# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView XML (xml/*.xml), the VTK classes and the property reference agree.

For every property of every proxy whose command is a Set method with a matching Get:
- its default_values equal what a freshly constructed filter returns;
- each bound of its DoubleRangeDomain / IntRangeDomain / IdTypeRangeDomain (or the entries of
  its EnumerationDomain) equals the class's clamp: GetXMinValue / GetXMaxValue where
  vtkSetClampMacro defines them, else what Set returns for a value far outside; a bound the
  XML leaves open must be open in the class too, and a class that clamps needs a domain;
every row of docs/PROPERTIES.md (the reference the README links to, one table per proxy) gives
the XML's default, and every property has its row; and the class
comment of each property in the class's header (Filters/<class>.h) states the class's default:
"Default 0.1", "(default on)", "0 (default)" in a block of one property, "Defaults: A 1, B 0"
in a block of several, except in a header whose parameters come from one table
(<class>_PARAMETERS, CONTRIBUTING.md, "Adding a parameter"): there the getters read the core's fields,
whose initialisers are the defaults, and the header states none (the XML is where prose does).
Plain VTK Python (/usr/bin/python3)."""
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

from vtkmodules.vtkCommonCore import vtkObject

import deformablesurface

# Properties compared by hand or not at all, and why.
EXCEPTIONS = {
    # Set/Get with another meaning than the XML element: an input array choice, a list
    # filled by repeated Add calls or by index (the seed points and their objects), a file name
    # (no default), reported time steps, a text (the DICOM reader's series description, empty by
    # default).
    "Scalars", "RemovedTetrahedra", "Points", "ObjectIds", "FileName", "TimestepValues",
    "SeriesDescription", "ObjectIntensityRanges",
}
# Clamped by the class without a range domain in the XML, because ParaView 5.11 has none for
# IdTypeVectorProperty: the property's documentation must state the bound (this text).
UNRANGED = {"DeformableSurface.MaxVertices": "at least 4"}
# How far outside any range the probes go, and what an open bound looks like, per type.
PROBE = {"DoubleVectorProperty": 1e300, "IntVectorProperty": 2 ** 31 - 1, "IdTypeVectorProperty": 2 ** 62}
RANGE_DOMAINS = ("DoubleRangeDomain", "IntRangeDomain", "IdTypeRangeDomain")

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..", "..")
failures = []
checked = 0


def parse(kind, text):
    return float(text) if kind == "DoubleVectorProperty" else int(text)


def class_bound(obj, name, kind, side):
    """The class's lower (side 0) or upper (side 1) clamp for property `name`."""
    macro = getattr(obj, "Get%s%sValue" % (name, ("Min", "Max")[side]), None)
    if macro is not None:
        return macro()
    before = getattr(obj, "Get" + name)()
    getattr(obj, "Set" + name)(-PROBE[kind] if side == 0 else PROBE[kind])
    bound = getattr(obj, "Get" + name)()
    getattr(obj, "Set" + name)(before)
    return bound


def xml_bounds(prop, kind):
    """(min, max) the XML allows, None for an open side; None when it has no range at all."""
    for tag in RANGE_DOMAINS:
        domain = prop.find(tag)
        if domain is not None:
            return tuple(parse(kind, domain.get(k)) if domain.get(k) is not None else None for k in ("min", "max"))
    enum = prop.find("EnumerationDomain")
    if enum is not None:
        values = [int(e.get("value")) for e in enum.findall("Entry")]
        return (min(values), max(values))
    return None


def is_open(value, kind):
    """A clamp at the type's limit (VTK_DOUBLE_MAX is 1e299, VTK_INT_MAX, VTK_ID_MAX)."""
    return abs(value) >= (1e299 if kind == "DoubleVectorProperty" else PROBE[kind])


def check_property(proxy_name, obj, prop):
    global checked
    name, kind = prop.get("name"), prop.tag
    where = "%s.%s" % (proxy_name, name)
    getter = getattr(obj, "Get" + name, None)
    if getter is None or prop.get("command") != "Set" + name:
        failures.append("%s: no Set%s/Get%s pair in %s (add it to EXCEPTIONS if meant)" %
                        (where, name, name, obj.GetClassName()))
        return
    checked += 1
    value = getter()
    got = tuple(value) if isinstance(value, (tuple, list)) else (value,)
    text = prop.get("default_values")
    if text is None:
        failures.append("%s: no default_values in the XML (the class starts at %s)" % (where, got))
    else:
        want = tuple(parse(kind, t) for t in text.split())
        if tuple(float(g) for g in got) != tuple(float(w) for w in want):
            failures.append("%s: XML default %s, %s starts at %s" % (where, text, obj.GetClassName(), got))
    if len(got) != 1 or prop.find("BooleanDomain") is not None:
        return  # vectors are not clamped; booleans are 0/1 by their domain
    bounds = xml_bounds(prop, kind)
    has_clamp = hasattr(obj, "Get%sMinValue" % name)
    if bounds is None:
        if where in UNRANGED:
            if UNRANGED[where] not in (prop.find("Documentation").text or ""):
                failures.append("%s: the documentation does not say '%s'" % (where, UNRANGED[where]))
        elif has_clamp:
            lo, hi = class_bound(obj, name, kind, 0), class_bound(obj, name, kind, 1)
            failures.append("%s: the class clamps to [%s, %s] but the XML has no range domain" % (where, lo, hi))
        return
    for side in (0, 1):
        cls = class_bound(obj, name, kind, side)
        xml = bounds[side]
        label = ("min", "max")[side]
        if xml is None:
            if not is_open(cls, kind):
                failures.append("%s: the XML %s is open, the class clamps at %s" % (where, label, cls))
        elif float(cls) != float(xml):
            failures.append("%s: XML %s %s, the class clamps at %s" % (where, label, xml, cls))


def reference_tables(path):
    """docs/PROPERTIES.md: {proxy label (its "## " heading): {property: default text}};
    `A`, `B` | x, y split in pairs."""
    tables, rows = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith("## "):
                rows = tables.setdefault(line[3:].strip(), {})
                continue
            cells = [c.strip() for c in line.split("|")]
            if rows is None or not line.startswith("| ") or len(cells) < 5 or "`" not in cells[2]:
                continue
            names = re.findall(r"`(\w+)`", cells[2])
            values = [v.strip() for v in re.split(r"\s*[,/]\s*", cells[3])]
            if len(values) == 1:
                values = values * len(names)
            for n, v in zip(names, values):
                rows[n] = v
    return tables


def readme_value(text, prop):
    """A documented default ('on', '2 000 000', '0 = all', 'Global maximum', '0 0') as XML values."""
    text = text.split(" = ")[0].strip()
    enum = prop.find("EnumerationDomain")
    if enum is not None:
        for entry in enum.findall("Entry"):
            if entry.get("text").lower() == text.lower():
                return entry.get("value")
    text = {"on": "1", "off": "0"}.get(text, text)
    if re.fullmatch(r"\d{1,3}( \d{3})+", text):
        text = text.replace(" ", "")
    return text


VALUE = r"\[[^\]]*\]|-?\d[\d ]*(?:\.\d+)?(?:e-?\d+)?(?:/\d+)?(?![\w.]\w)|on\b|off\b|[A-Z][A-Z_]+\b"


def header_value(text, cls):
    """A default as the header writes it ('2 000 000', '1/6', 'on', 'GLOBAL_MAXIMUM', '[0, 1]')
    as a tuple of floats."""
    text = text.strip()
    if text in ("on", "off"):
        return (float(text == "on"),)
    if re.fullmatch(r"[A-Z][A-Z_]+", text):
        return (float(getattr(cls, text)),)
    if text.startswith("["):
        return tuple(float(v) for v in text.strip("[]").split(","))
    text = text.replace(" ", "")
    if "/" in text:
        num, den = text.split("/")
        return (float(num) / float(den),)
    return (float(text),)


def check_header(cls, obj):
    """Each ///@{ ... ///@} block's stated defaults against a fresh object's Get values."""
    path = os.path.join(root, "Filters", cls.__name__ + ".h")
    with open(path) as f:
        header = f.read()
    if "#define %s_PARAMETERS(" % cls.__name__ in header:
        text = re.sub(r"\s+", " ", re.sub(r"^\s*(\*|///|//)", "", header, flags=re.M))
        for stated in re.findall(r"[Dd]efaults?:? (?:%s)|(?:%s) \((?:the )?default\)" % (VALUE, VALUE), text):
            failures.append("%s states a default ('%s'): the XML is the place" %
                            (os.path.basename(path), stated))
        return 0
    blocks = 0
    for block in re.findall(r"///@\{(.*?)///@\}", header, re.S):
        names = [a or b for a, b in re.findall(r"vtkSet\w*Macro\((\w+)|virtual void Set(\w+)\(", block)]
        names = [n for n in names if hasattr(obj, "Get" + n) and n not in EXCEPTIONS]
        if not names:
            continue
        blocks += 1
        text = re.sub(r"\s+", " ", re.sub(r"^\s*(\*|///)", "", block, flags=re.M))
        if len(names) == 1:
            stated = {names[0]: re.findall(r"[Dd]efault:? (%s)" % VALUE, text) +
                      re.findall(r"(%s) \((?:the )?default\)" % VALUE, text)}
        else:
            listed = re.search(r"[Dd]efaults: (.*?)(?:\)|\. |\.$)", text)
            pairs = re.findall(r"(\w+) (%s)" % VALUE, listed.group(1)) if listed else []
            stated = {n: [v for k, v in pairs if k == n] for n in names}
        for name, values in stated.items():
            value = getattr(obj, "Get" + name)()
            want = tuple(float(v) for v in (value if isinstance(value, (tuple, list)) else (value,)))
            if not values:
                failures.append("%s: the comment of %s states no default (the class's is %s)" %
                                (os.path.basename(path), name, want))
            for v in values:
                if header_value(v, cls) != want:
                    failures.append("%s: the comment of %s says default %s, the class's is %s" %
                                    (os.path.basename(path), name, v, want))
    return blocks


vtkObject.GlobalWarningDisplayOff()  # the probes outside the ranges warn (Gamma)
proxies = {}
header_blocks = 0
for path in sorted(glob.glob(os.path.join(root, "xml", "*.xml"))):
    for proxy in ET.parse(path).getroot().iter("SourceProxy"):
        cls = getattr(deformablesurface, proxy.get("class"), None)
        if cls is None and proxy.get("class") == "vtkDSDICOMSeriesReader":
            continue  # built without GDCM: the plugin leaves this XML out too
        proxies[proxy.get("name")] = proxy
        header_blocks += check_header(cls, cls())
        for prop in proxy:
            if prop.tag.endswith("VectorProperty") and prop.get("name") not in EXCEPTIONS:
                check_property(proxy.get("name"), cls(), prop)

# The reference's tables, one per proxy (docs/PROPERTIES.md, generated from the XML).
tables = reference_tables(os.path.join(root, "docs", "PROPERTIES.md"))
rows = 0
for proxy_name, proxy in proxies.items():
    table = tables.get(proxy.get("label", proxy_name))
    if table is None:
        failures.append("docs/PROPERTIES.md: no table for %s" % proxy_name)
        continue
    for prop in proxy:
        name = prop.get("name")
        if not prop.tag.endswith("VectorProperty") or name in EXCEPTIONS or prop.get("information_only") == "1":
            continue
        if name not in table:
            failures.append("docs/PROPERTIES.md: the table has no row for %s.%s" % (proxy_name, name))
            continue
        rows += 1
        got = readme_value(table[name], prop)
        want = prop.get("default_values")
        if [float(v) for v in got.split()] != [float(v) for v in want.split()]:
            failures.append("docs/PROPERTIES.md: %s.%s defaults to '%s', %s in the XML"
                            % (proxy_name, name, table[name], want))

print("checked %d properties of %d proxies, %d reference rows, %d header comments" %
      (checked, len(proxies), rows, header_blocks))
for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures or checked < 30 or rows < 30 else 0)
