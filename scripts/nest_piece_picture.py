#!/usr/bin/env python3
"""One piece of a grading nest as a picture: the piece's outline on every size, one
colour per size, with a legend (for the README's nest of the wetsuit's front torso).

Usage: scripts/nest_piece_picture.py DIR/nest.svg PIECE OUT.svg
(then e.g. `rsvg-convert -w 500 -b white OUT.svg -o OUT.png`). The nest is the 1:1 SVG
that `tightfit grade` writes; its groups are named piece-PIECE_SIZE.
"""
import copy
import re
import sys
import xml.etree.ElementTree as ET

SVG = 'http://www.w3.org/2000/svg'
COLOURS = ['#1f4fd0', '#c0392b', '#27864a', '#b8860b', '#7b3fa0', '#333333']


def main(nest_file, piece, out_file):
    root = ET.parse(nest_file).getroot()
    prefix = 'piece-' + piece + '_'
    groups = [g for g in root.findall('{%s}g' % SVG) if g.get('id', '').startswith(prefix)]
    if not groups:
        sys.exit('%s: no piece "%s" in the nest' % (nest_file, piece))
    xs, ys = [], []
    for g in groups:
        for p in g.iter('{%s}path' % SVG):
            numbers = [float(n) for n in re.findall(r'-?\d+\.?\d*', p.get('d', ''))]
            xs += numbers[0::2]
            ys += numbers[1::2]
    x0, x1, y0, y1 = min(xs) - 15, max(xs) + 15, min(ys) - 15, max(ys) + 20 + 24 * len(groups)
    out = ET.Element('{%s}svg' % SVG, {'width': '%.0fmm' % (x1 - x0), 'height': '%.0fmm' % (y1 - y0),
                                        'viewBox': '%.1f %.1f %.1f %.1f' % (x0, y0, x1 - x0, y1 - y0)})
    ET.SubElement(out, '{%s}rect' % SVG, {'x': str(x0), 'y': str(y0), 'width': str(x1 - x0),
                                          'height': str(y1 - y0), 'fill': 'white'})
    style = ET.SubElement(out, '{%s}style' % SVG)
    style.text = 'path, line { fill: none; stroke-linecap: round; stroke-linejoin: round; } .sew, text { display: none; }'
    for k, g in enumerate(groups):
        size = g.get('id')[len(prefix):]
        colour = COLOURS[k % len(COLOURS)]
        copied = copy.deepcopy(g)
        for e in copied.iter():
            if e.tag.endswith('path') or e.tag.endswith('line'):
                e.set('stroke', colour)
                e.set('stroke-width', '1.2')
        out.append(copied)
        label = ET.SubElement(out, '{%s}text' % SVG, {
            'x': str(x0 + 10), 'y': str(y1 - 10 - 24 * (len(groups) - 1 - k)), 'font-size': '20',
            'fill': colour, 'style': 'display: inline; font-family: sans-serif'})
        label.text = size
    ET.register_namespace('', SVG)
    ET.ElementTree(out).write(out_file)


if __name__ == '__main__':
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
