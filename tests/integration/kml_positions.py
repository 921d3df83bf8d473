#!/usr/bin/env python3
"""Reads a KML 2.2 file as an XML parser does and prints what it holds, one
JSON object: the NetworkLink hrefs, every time-stamped Point (folder name,
seconds since the epoch, lon, lat, altitude), and every LineString's
coordinates by Placemark name. Exits 1 (with the reason) when the file is
not well-formed XML or its root is not KML 2.2's <kml>."""
import json
import sys
import xml.etree.ElementTree as ET
from datetime import datetime

NS = "{http://www.opengis.net/kml/2.2}"


def coordinates(element):
    text = element.findtext(NS + "coordinates") or ""
    return [[float(v) for v in c.split(",")] for c in text.split()]


def main(path):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as error:
        print(f"{path}: not well-formed XML: {error}")
        return 1
    if root.tag != NS + "kml":
        print(f"{path}: root is {root.tag}, not KML 2.2's {NS}kml")
        return 1
    out = {"hrefs": [], "stamped": [], "lines": {}, "points": {}}
    for link in root.iter(NS + "Link"):
        out["hrefs"].append(link.findtext(NS + "href"))
    for folder in [root.find(NS + "Document")] + list(root.iter(NS + "Folder")):
        folder_name = folder.findtext(NS + "name")
        for placemark in folder.findall(NS + "Placemark"):
            name = placemark.findtext(NS + "name") or folder_name
            when = placemark.findtext(NS + "TimeStamp/" + NS + "when")
            point = placemark.find(NS + "Point")
            line = placemark.find(NS + "LineString")
            if when is not None and point is not None:
                seconds = datetime.fromisoformat(when.replace("Z", "+00:00")).timestamp()
                out["stamped"].append([folder_name, seconds] + coordinates(point)[0])
            elif point is not None:
                out["points"][name] = coordinates(point)[0]
            if line is not None:
                out["lines"][name] = coordinates(line)
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
