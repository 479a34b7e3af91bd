# Makes deep_composites.ttf for tests/readers.rs (fontTools): glyph "base" (one contour), a
# chain of 40 composites c0..c39 each holding the one before (c32 on is nested more than 32
# deep), and two composites loopa and loopb that hold each other. Run: python3 deep_composites.py OUT.ttf
from fontTools.fontBuilder import FontBuilder
from fontTools.pens.ttGlyphPen import TTGlyphPen
from fontTools.ttLib.tables._g_l_y_f import Glyph, GlyphComponent
N=40
names=[".notdef","base"]+["c%d"%i for i in range(N)]+["loopa","loopb"]
fb=FontBuilder(1000,isTTF=True)
fb.setupGlyphOrder(names)
fb.setupCharacterMap({65:"c%d"%(N-1)})
pen=TTGlyphPen(None); pen.moveTo((0,0)); pen.lineTo((100,0)); pen.qCurveTo((150,50),(100,100)); pen.closePath()
g={".notdef":TTGlyphPen(None).glyph(),"base":pen.glyph()}
prev="base"
for i in range(N):
    gl=Glyph(); gl.numberOfContours=-1
    c=GlyphComponent(); c.glyphName=prev; c.x=1; c.y=0; c.flags=0
    gl.components=[c]
    g["c%d"%i]=gl; prev="c%d"%i
g["loopa"]=TTGlyphPen(None).glyph(); g["loopb"]=TTGlyphPen(None).glyph()
fb.setupGlyf(g)
for a,b in (("loopa","loopb"),("loopb","loopa")):
    gl=Glyph(); gl.numberOfContours=-1
    c=GlyphComponent(); c.glyphName=b; c.x=0; c.y=0; c.flags=0
    gl.components=[c]; gl.xMin=gl.yMin=0; gl.xMax=gl.yMax=100
    fb.font["glyf"].glyphs[a]=gl
fb.setupHorizontalMetrics({n:(500,0) for n in names})
fb.setupHorizontalHeader(ascent=800,descent=-200)
fb.setupNameTable({"familyName":"Deep","styleName":"Regular"})
fb.setupOS2(); fb.setupPost()
fb.font.recalcBBoxes=False
fb.save(__import__("sys").argv[1] if len(__import__("sys").argv) > 1 else "deep_composites.ttf")
