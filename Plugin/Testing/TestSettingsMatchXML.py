"""The ParaView XML states the LAO settings as the one definition does
(cao::LAOSettingTable, read through vtkLocalAmbientOcclusion's static
GetSetting* methods):

  TestSettingsMatchXML.py PLUGIN.so

For the LocalAmbientOcclusion filter proxy (property = the setting's name)
and the ContextualAOVolumeRepresentation proxy (property = "AO" + name),
every setting of the table has a property whose command is Set<name>, an
integer property exactly when the setting is an integer, the table's
default, and a domain inside the table's range (a slider may stop short of
the limit, never go past it); an enumeration offers every value of the
range. The VTK filter's and mapper's own defaults are the table's too.

Negative control: the same comparison against a table with one default
and one limit changed reports both.

The view's Surface AO Method list offers None and every registered surface
technique (vtkContextualAOPass::GetRegisteredMethods), nothing else
(negative control: one more technique than the list offers is caught), and
the Line AO Method list None and every registered line technique
(GetRegisteredLineMethods), with the same control."""
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin

from contextualao import vtkContextualAOVolumeMapper
from contextualao import vtkLocalAmbientOcclusion as LAO

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


LoadPlugin(sys.argv[1], remote=False, ns=globals())
table = [dict(name=LAO.GetSettingName(i), default=LAO.GetSettingDefault(i),
              minimum=LAO.GetSettingMinimum(i), maximum=LAO.GetSettingMaximum(i),
              integer=LAO.GetSettingIsInteger(i)) for i in range(LAO.GetNumberOfSettings())]
check([r["name"] for r in table] == ["RayPattern", "NumberOfRays", "Reach", "NumberOfSamples",
                                     "SampleDensity", "StartOffset", "RayVariation",
                                     "Quality"],
      "the table names the eight LAO settings: %s" % [r["name"] for r in table])

pxm = servermanager.ProxyManager()
proxies = {"LocalAmbientOcclusion": (pxm.NewProxy("filters", "LocalAmbientOcclusion"), ""),
           "ContextualAOVolumeRepresentation":
           (pxm.NewProxy("representations", "ContextualAOVolumeRepresentation"), "AO")}


def domain_range(prop):
    """(min or None, max or None, enumeration values or None) of a property."""
    it = prop.NewDomainIterator()
    it.Begin()
    lo = hi = values = None
    while not it.IsAtEnd():
        d = it.GetDomain()
        if d.IsA("vtkSMEnumerationDomain"):
            values = sorted(d.GetEntryValue(i) for i in range(d.GetNumberOfEntries()))
        elif d.IsA("vtkSMIntRangeDomain") or d.IsA("vtkSMDoubleRangeDomain"):
            if d.GetMinimumExists(0):
                lo = d.GetMinimum(0)
            if d.GetMaximumExists(0):
                hi = d.GetMaximum(0)
        it.Next()
    return lo, hi, values


def mismatches(rows, proxy, prefix):
    found = []
    for r in rows:
        name = prefix + r["name"]
        prop = proxy.GetProperty(name)
        if prop is None:
            found.append("%s: no property" % name)
            continue
        if prop.GetCommand() != "Set" + r["name"]:
            found.append("%s: command %s" % (name, prop.GetCommand()))
        is_int = prop.IsA("vtkSMIntVectorProperty")
        if is_int != r["integer"]:
            found.append("%s: %s property for a%s setting" % (
                name, "an integer" if is_int else "a double", "n integer" if r["integer"] else
                " real"))
        prop.ResetToXMLDefaults()
        default = prop.GetElement(0)
        if default != r["default"]:
            found.append("%s: default %r, the table's %r" % (name, default, r["default"]))
        lo, hi, values = domain_range(prop)
        if values is not None:
            want = list(range(int(r["minimum"]), int(r["maximum"]) + 1))
            if values != want:
                found.append("%s: enumeration %s, the table's range %s" % (name, values, want))
        if lo is not None and lo < r["minimum"]:
            found.append("%s: domain minimum %r below the table's %r" % (name, lo, r["minimum"]))
        if hi is not None and hi > r["maximum"]:
            found.append("%s: domain maximum %r above the table's %r" % (name, hi, r["maximum"]))
    return found


for label, (proxy, prefix) in proxies.items():
    found = mismatches(table, proxy, prefix)
    check(not found, "%s states every LAO setting as the table does%s" % (
        label, (": " + "; ".join(found)) if found else ""))

# The VTK objects' own defaults.
for label, obj in (("vtkLocalAmbientOcclusion", LAO()),
                   ("vtkContextualAOVolumeMapper", vtkContextualAOVolumeMapper())):
    wrong = ["%s=%r" % (r["name"], getattr(obj, "Get" + r["name"])()) for r in table
             if getattr(obj, "Get" + r["name"])() != r["default"]]
    check(not wrong, "%s's defaults are the table's%s" % (label, (": " + ", ".join(wrong))
                                                         if wrong else ""))

# Negative control: a changed default and a narrower limit are both reported.
altered = [dict(r) for r in table]
altered[0]["default"] = 3  # RayPattern
altered[5]["maximum"] = 0.5  # StartOffset
found = mismatches(altered, proxies["LocalAmbientOcclusion"][0], "")
check(len(found) == 2 and "RayPattern" in found[0] and "StartOffset" in found[1],
      "negative control: an altered table is caught (%s)" % "; ".join(found))

# The view's Surface AO Method list offers None and every registered
# surface technique (vtkCAOSurfaceTechnique.h), by value, and nothing else:
# a built-in technique registered without its XML entry, or an entry with
# no technique behind it, is caught.
from contextualao import vtkContextualAOPass  # noqa: E402



def parse(listing):
    return [(int(v), n) for v, n in (e.split(" ", 1) for e in listing.split(", "))]


registered = parse(vtkContextualAOPass.GetRegisteredMethods())


def method_mismatch(offered, techniques):
    want = [0] + sorted(v for v, _ in techniques)
    return None if offered == want else "offered %s, None and the registered %s" % (offered, want)


view = pxm.NewProxy("views", "ContextualAORenderView")
offered = domain_range(view.GetProperty("SurfaceAOMethod"))[2]
wrong = method_mismatch(offered, registered)
check(registered and wrong is None,
      "the view's Surface AO Method list is None and the registered techniques (%s)%s"
      % (vtkContextualAOPass.GetRegisteredMethods(), (": " + wrong) if wrong else ""))
# Negative control: one more registered technique than the list offers.
check(method_mismatch(offered, registered + [(40, "flat")]) is not None,
      "negative control: a technique the list lacks is caught")
# The same for the lines: the Line AO Method list is None and every
# registered line technique (vtkCAOLineTechnique.h).
lines_registered = parse(vtkContextualAOPass.GetRegisteredLineMethods())
lines_offered = domain_range(view.GetProperty("LineAOMethod"))[2]
wrong = method_mismatch(lines_offered, lines_registered)
check(lines_registered and wrong is None,
      "the view's Line AO Method list is None and the registered line techniques (%s)%s"
      % (vtkContextualAOPass.GetRegisteredLineMethods(), (": " + wrong) if wrong else ""))
check(method_mismatch(lines_offered, lines_registered + [(40, "half")]) is not None,
      "negative control: a line technique the list lacks is caught")


# The representation's groups in the panel only with "Contextual AO
# Volume" (as ParaView's own groups are shown only with theirs): every
# PropertyGroup the Extension exposes holds a visibility decorator on
# Representation with that value. (Negative control: the same check on a
# copy with one decorator removed.)
def groups_without_decorator(root):
    missing = []
    for extension in root.iter("Extension"):
        for group in extension.iter("PropertyGroup"):
            found = any(d.get("property") == "Representation" and d.get("value") == "Contextual AO Volume"
                        for d in group.iter("PropertyWidgetDecorator"))
            if not found:
                missing.append(group.get("label"))
    return missing


import copy  # noqa: E402
import os  # noqa: E402
import xml.etree.ElementTree as ET  # noqa: E402

xml_root = ET.parse(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                                 "ContextualAORepresentation.xml")).getroot()
missing = groups_without_decorator(xml_root)
groups = [g.get("label") for e in xml_root.iter("Extension") for g in e.iter("PropertyGroup")]
check(len(groups) >= 4 and not missing,
      "each exposed group (%s) is shown only with Contextual AO Volume%s"
      % (groups, (": not " + ", ".join(missing)) if missing else ""))
control = copy.deepcopy(xml_root)
first = next(g for e in control.iter("Extension") for g in e.iter("PropertyGroup"))
for hints in first.findall("Hints"):
    first.remove(hints)
check(groups_without_decorator(control) == [first.get("label")],
      "negative control: a group without the decorator is caught")

if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
