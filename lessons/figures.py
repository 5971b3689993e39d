#!/usr/bin/env python3
"""Pictures for the lessons that the engine does not draw by itself.

Pure Python 3 (no numpy, no PIL, no fonts), so it runs anywhere `make-images.sh` runs. Each figure is a
subcommand; the engine's renders come in as PFM files (raw floats, written by `opengl3d render
--out X.pfm`), and everything goes out as 8-bit RGB PNG. `--lang ja` before the subcommand writes the
labels in Japanese (the Japanese pages use those variants, from img/ja/).

    python3 figures.py [--lang ja] depth-curve OUT.png
    python3 figures.py spiral OUT.png
    python3 figures.py mip-chain LINEAR_DEPTH_1280x720.pfm OUT.png
    python3 figures.py course-depth LINEAR_DEPTH_1280x720.pfm OUT.png
    python3 figures.py normals LINEAR_DEPTH_1280x720.pfm OUT.png
    python3 figures.py grid OUT.png W H LABEL=FILE.pfm@X,Y ...   (W x H crops, 2 per row)
    python3 figures.py --lang ja error-legend ERROR.png ERROR.pfm OUT.png [RANGE]
        (the engine's error map, `render --view error`, its scale's words in Japanese)
    python3 figures.py glyphs UNIFONT.hex... TEXT   (prints JA_GLYPHS entries that TEXT lacks)
"""

import math
import struct
import sys
import zlib

NEAR, FAR, FOV_Y = 0.35, 1000.0, 60.0

# ---------------------------------------------------------------------------------------------
# A 5x7 bitmap font: just the characters the figures use.
FONT = {
    "0": ["01110", "10001", "10011", "10101", "11001", "10001", "01110"],
    "1": ["00100", "01100", "00100", "00100", "00100", "00100", "01110"],
    "2": ["01110", "10001", "00001", "00010", "00100", "01000", "11111"],
    "3": ["11110", "00001", "00001", "01110", "00001", "00001", "11110"],
    "4": ["00010", "00110", "01010", "10010", "11111", "00010", "00010"],
    "5": ["11111", "10000", "11110", "00001", "00001", "10001", "01110"],
    "6": ["00110", "01000", "10000", "11110", "10001", "10001", "01110"],
    "7": ["11111", "00001", "00010", "00100", "01000", "01000", "01000"],
    "8": ["01110", "10001", "10001", "01110", "10001", "10001", "01110"],
    "9": ["01110", "10001", "10001", "01111", "00001", "00010", "01100"],
    ".": ["00000", "00000", "00000", "00000", "00000", "01100", "01100"],
    ",": ["00000", "00000", "00000", "00000", "01100", "00100", "01000"],
    "-": ["00000", "00000", "00000", "11111", "00000", "00000", "00000"],
    "+": ["00000", "00100", "00100", "11111", "00100", "00100", "00000"],
    "=": ["00000", "00000", "11111", "00000", "11111", "00000", "00000"],
    "(": ["00010", "00100", "01000", "01000", "01000", "00100", "00010"],
    ")": ["01000", "00100", "00010", "00010", "00010", "00100", "01000"],
    ":": ["00000", "01100", "01100", "00000", "01100", "01100", "00000"],
    "/": ["00001", "00010", "00010", "00100", "01000", "01000", "10000"],
    "*": ["00000", "10101", "01110", "11111", "01110", "10101", "00000"],
    " ": ["00000"] * 7,
    "a": ["00000", "00000", "01110", "00001", "01111", "10001", "01111"],
    "b": ["10000", "10000", "10110", "11001", "10001", "10001", "11110"],
    "c": ["00000", "00000", "01110", "10000", "10000", "10001", "01110"],
    "d": ["00001", "00001", "01101", "10011", "10001", "10001", "01111"],
    "e": ["00000", "00000", "01110", "10001", "11111", "10000", "01110"],
    "f": ["00110", "01001", "01000", "11100", "01000", "01000", "01000"],
    "g": ["00000", "01111", "10001", "10001", "01111", "00001", "01110"],
    "h": ["10000", "10000", "10110", "11001", "10001", "10001", "10001"],
    "i": ["00100", "00000", "01100", "00100", "00100", "00100", "01110"],
    "k": ["10000", "10000", "10010", "10100", "11000", "10100", "10010"],
    "l": ["01100", "00100", "00100", "00100", "00100", "00100", "01110"],
    "m": ["00000", "00000", "11010", "10101", "10101", "10001", "10001"],
    "n": ["00000", "00000", "10110", "11001", "10001", "10001", "10001"],
    "o": ["00000", "00000", "01110", "10001", "10001", "10001", "01110"],
    "p": ["00000", "00000", "11110", "10001", "11110", "10000", "10000"],
    "r": ["00000", "00000", "10110", "11001", "10000", "10000", "10000"],
    "s": ["00000", "00000", "01110", "10000", "01110", "00001", "11110"],
    "t": ["01000", "01000", "11100", "01000", "01000", "01001", "00110"],
    "u": ["00000", "00000", "10001", "10001", "10001", "10011", "01101"],
    "v": ["00000", "00000", "10001", "10001", "10001", "01010", "00100"],
    "w": ["00000", "00000", "10001", "10001", "10101", "10101", "01010"],
    "x": ["00000", "00000", "10001", "01010", "00100", "01010", "10001"],
    "y": ["00000", "00000", "10001", "10001", "01111", "00001", "01110"],
    "z": ["00000", "00000", "11111", "00010", "00100", "01000", "11111"],
    "A": ["01110", "10001", "10001", "11111", "10001", "10001", "10001"],
    "B": ["11110", "10001", "10001", "11110", "10001", "10001", "11110"],
    "C": ["01110", "10001", "10000", "10000", "10000", "10001", "01110"],
    "D": ["11100", "10010", "10001", "10001", "10001", "10010", "11100"],
    "L": ["10000", "10000", "10000", "10000", "10000", "10000", "11111"],
    "N": ["10001", "11001", "10101", "10011", "10001", "10001", "10001"],
    "O": ["01110", "10001", "10001", "10001", "10001", "10001", "01110"],
    "S": ["01111", "10000", "10000", "01110", "00001", "00001", "11110"],
}


# Glyphs for the Japanese labels: 16 rows of a 16-pixel (or 8-pixel) wide bitmap each, as hex, from
# GNU Unifont (SIL Open Font License 1.1; Japanese forms from unifont_jp.hex). Only the characters
# the labels use; `figures.py glyphs /usr/share/unifont/unifont_jp.hex /usr/share/unifont/unifont.hex
# TEXT` prints the lines for new ones (Debian package unifont).
JA_GLYPHS = {
    "×": "00000000000000422418244200000000",
    "、": "000000000000000000000000000010000C000600020000000000000000000000",
    "あ": "00000100010001601F800200022003F806240A421282210222041C0800300000",
    "い": "0000000000001000100010101008100810041004100409000A00040000000000",
    "き": "0100010001600F80008000B80FC00040002007D00830100010000C0003C00000",
    "し": "000004000400040004000400040004000400040004040408023001C000000000",
    "な": "00000400040007883C0404020820082010202020002001E00238022401C00000",
    "の": "00000000000001E0069808841084108221022102220412040C18006000000000",
    "ま": "0000008000801FF80080008000800FF00080008000800FC010B010880F000000",
    "り": "00000010081008100810081008100A100C100410001000200020004001800000",
    "ア": "0000000000001FFC000400880090008000800080010001000200040000000000",
    "イ": "0000000000100010002000400080018006801880008000800080008000800000",
    "ウ": "00000080008000801FFC10041004100400040008000800100060018000000000",
    "ェ": "00000000000000000000000000000000000007F000800080008000800FF80000",
    "カ": "01000100010001003FFC01040104020402040404040408081008207000000000",
    "ケ": "0000020002000200040007FE0810101020100020002000400080030000000000",
    "ス": "0000000000000FF00010001000200020004000A0011002080404180400000000",
    "ッ": "0000000000000000000000000000000001000888048804100010002000400080",
    "ト": "00000200020002000200020003C0023002080200020002000200020002000000",
    "バ": "000000000004000A040404400420081008081004100420024002000000000000",
    "プ": "0006000900091FFE000400040004000800080010002000400180060000000000",
    "ベ": "0000000000000000001006280910108020404020001800060000000000000000",
    "ミ": "000000000380006000100000030000C00020000000000E000180006000100000",
    "メ": "000000000008000800080010031000A000600050008801000600180000000000",
    "ラ": "0000000007F00000000000001FFC0004000800080010002000C0030000000000",
    "ル": "000000000040004004400440044004400440084008411042204C407000000000",
    "レ": "00000000040004000400040004000400040004080410042004C0070000000000",
    "ー": "000000000000000000000000000020001FFE0000000000000000000000000000",
    "低": "080E0BF00A1012101210321053FF121012101208120813881605100517F20000",
    "修": "0840084008FF11841648343054CC171314E01408143014C21004101811E00000",
    "値": "082008200FFF104011FC350455FC1504150415FC1504150415FC140017FF0000",
    "再": "00003FFE008000801FFC108410841FFC108410847FFF100410041004101C0000",
    "分": "0060042004100810080810042FFA410901080108020802080410081010E00000",
    "判": "24821482152204223FA20422042204227FA204220422040204020402040E0000",
    "前": "081004207FFE00003E04224422443E44224422443E44224422042204261C0000",
    "割": "040204027FD2405244523F9204123F9204127FD200123F82208220823F8E0000",
    "半": "10840884088800803FFE0080008000807FFF0080008000800080008000800000",
    "古": "0100010001007FFE01000100010001001FF8100810081008100810081FF80000",
    "可": "000000007FFF000800081F8810881088108810881F8800080008000800380000",
    "合": "0080014002200410180C600307F0000000000FF808080808080808080FF80000",
    "回": "00007FFE40024002400247E2442244224422442247E24002400240027FFE0000",
    "境": "1020102013FE1104788817FF100011FC110411FC190461FC009103110C0F0000",
    "定": "008000803FFE200220020FF800800880088008F8088018801480238040FF0000",
    "巻": "0888048804901FFC014002207FFF04100FF81814601307F00400040403FC0000",
    "平": "00003FFE0080088808880490049000807FFF0080008000800080008000800000",
    "度": "004000401FFF1000110817FE110811F8100017FC11082090206041980E070000",
    "径": "080013FC2004410808901060319856071020102013FE10201020102017FF0000",
    "後": "08401088211040A00844108E37F1508111FC120414881050102010D817070000",
    "接": "1020102013FE1104788817FF102010201FFF7084110413C8103010CC37020000",
    "数": "2490149015107FBF0E22156224A248227FD4091411083A080614192260C10000",
    "既": "00003EFE224822483E48224822FF3E1020102418242824282A49328961070000",
    "果": "00001FFC108410841FFC108410841FFC00807FFF02A00490188C608300800000",
    "正": "00003FFC0080008000800880088008F80880088008800880088008807FFE0000",
    "深": "200013FE0A02025240502091130F002008200BFF10A811242222242140200000",
    "界": "00001FFC108410841FFC108410841FFC022004101C1C64130410081010100000",
    "結": "0810101021FF14100810121026FE790009002AFE2A8249824882088208FE0000",
    "線": "0810102022FE148208FE1282268279FE091129DA2C5C4A944A92091108300000",
    "能": "10401246277878C000413F41213F21403F46217821403F4021412141233F0000",
    "距": "00003EFE2280228022803EFE0882088228822EFE288028802E80388060FF0000",
    "離": "082408247F28007F55C84948557E7F4808487F48497E55487B484148437F0000",
    "面": "00003FFE008001003FFE2222222223E22222222223E22222222222223FFE0000",
    "ぎ": "01000104016A0F84008000B80FC00040002007D00830100010000C0003C00000",
    "す": "0000004000403FFC0040004003C00440044004C0034000400080010006000000",
    "る": "0000000007F0002000400080010002F007080804100401840248023001E00000",
    "大": "00800080008000803FFE00800080014001400220022004100808100420020000",
    "明": "0000007E3E4222422242227E3E4222422242227E3E42008200820102060E0000",
    "暗": "0040004003FC7908488848904FFF780049F84908490879F80108010801F80000",
    "最": "1FF810081FF810081FF800007FFE12001EFC12441E4412281E10622802C60000",
    "ク": "0000000004000270039002200420044008401080008001000200040008000000",
    "セ": "000000000800040004000478058826101C20044004000400020001F000000000",
    "テ": "00000000000011E00E000000007823801C800080010001000200040008000000",
}


def wide_glyph(ch):
    """(16 row bitmaps as ints, width) of a character outside the 5x7 font."""
    hexbits = JA_GLYPHS.get(ch)
    if hexbits is None:
        sys.exit("figures.py: no glyph for %r (U+%04X); add it to JA_GLYPHS with the glyphs subcommand" % (ch, ord(ch)))
    w = len(hexbits) // 4  # 32 hex digits: 8 wide, 64: 16 wide
    step = w // 4
    return [int(hexbits[i:i + step], 16) for i in range(0, len(hexbits), step)], w


def char_advance(ch, scale):
    if ch in FONT:
        return 6 * scale
    return round(wide_glyph(ch)[1] * scale / 2) + scale // 2


def glyph_lines(hex_files, text):
    """JA_GLYPHS entries for the characters of `text` that have none yet (first file that has one wins)."""
    wanted = sorted({ch for ch in text if ch not in FONT and ch not in JA_GLYPHS})
    found = {}
    for path in hex_files:
        for line in open(path, encoding="ascii"):
            code, _, bits = line.strip().partition(":")
            ch = chr(int(code, 16))
            if ch in wanted and ch not in found:
                found[ch] = bits
    for ch in wanted:
        if ch in found:
            print('    "%s": "%s",' % (ch, found[ch]))
        else:
            print("no glyph for %r" % ch, file=sys.stderr)


LANG = "en"

# Words on the figures, per language.
WORDS = {
    "distance": {"en": "distance (m)", "ja": "距離(m)"},
    "turns": {"en": "%d turns, 100-texel disc", "ja": "巻き回数%d、半径100テクセル"},
    "level": {"en": "level %d", "ja": "レベル%d"},
    "level-size": {"en": "level %d  %dx%d", "ja": "レベル%d  %d×%d"},
    "max": {"en": "max %s", "ja": "最大 %s"},
    "too-dark": {"en": "%s too dark", "ja": "%s 暗すぎ"},
    "too-light": {"en": "too light %s", "ja": "明るすぎ %s"},
}


def words(key):
    return WORDS[key][LANG]


class Image:
    def __init__(self, w, h, bg=(255, 255, 255)):
        self.w, self.h = w, h
        self.px = bytearray(bytes(bg) * (w * h))

    def set(self, x, y, c):
        x, y = int(x), int(y)
        if 0 <= x < self.w and 0 <= y < self.h:
            i = 3 * (y * self.w + x)
            self.px[i:i + 3] = bytes(c)

    def rect(self, x0, y0, x1, y1, c):
        for y in range(max(0, int(y0)), min(self.h, int(y1))):
            for x in range(max(0, int(x0)), min(self.w, int(x1))):
                self.set(x, y, c)

    def line(self, x0, y0, x1, y1, c, width=1, dash=0):
        n = int(max(abs(x1 - x0), abs(y1 - y0))) + 1
        r = (width - 1) / 2
        for i in range(n + 1):
            if dash and (i // dash) % 2:
                continue
            t = i / n
            x, y = x0 + (x1 - x0) * t, y0 + (y1 - y0) * t
            for dy in range(-int(r), int(r) + 1):
                for dx in range(-int(r), int(r) + 1):
                    self.set(round(x + dx), round(y + dy), c)

    def disc(self, cx, cy, rad, c):
        for y in range(int(cy - rad) - 1, int(cy + rad) + 2):
            for x in range(int(cx - rad) - 1, int(cx + rad) + 2):
                if (x + 0.5 - cx) ** 2 + (y + 0.5 - cy) ** 2 <= rad * rad:
                    self.set(x, y, c)

    def circle(self, cx, cy, rad, c, dash=0):
        n = int(2 * math.pi * rad) + 1
        for i in range(n):
            if dash and (i // dash) % 2:
                continue
            a = 2 * math.pi * i / n
            self.set(cx + rad * math.cos(a), cy + rad * math.sin(a), c)

    def text(self, x, y, s, c=(0, 0, 0), scale=2):
        for ch in s:
            if ch in FONT:
                for gy, row in enumerate(FONT[ch]):
                    for gx, bit in enumerate(row):
                        if bit == "1":
                            self.rect(x + gx * scale, y + gy * scale, x + (gx + 1) * scale, y + (gy + 1) * scale, c)
            else:
                # 16-pixel glyphs drawn at scale/2, so at scale 2 they stand as tall as the 5x7 ones
                # (7 rows x 2) plus one pixel above and below.
                bits, w = wide_glyph(ch)
                k = scale / 2
                for gy, row in enumerate(bits):
                    for gx in range(w):
                        if row >> (w - 1 - gx) & 1:
                            self.rect(x + gx * k, y - k + gy * k, x + (gx + 1) * k, y - k + (gy + 1) * k, c)
            x += char_advance(ch, scale)

    def text_width(self, s, scale=2):
        return sum(char_advance(ch, scale) for ch in s) - scale

    def paste(self, other, ox, oy):
        for y in range(other.h):
            if 0 <= oy + y < self.h:
                for x in range(other.w):
                    i = 3 * (y * other.w + x)
                    self.set(ox + x, oy + y, other.px[i:i + 3])

    def save(self, path):
        raw = b"".join(b"\x00" + bytes(self.px[3 * y * self.w:3 * (y + 1) * self.w]) for y in range(self.h))

        def chunk(kind, data):
            return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

        png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", self.w, self.h, 8, 2, 0, 0, 0))
        png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
        with open(path, "wb") as f:
            f.write(png)


def read_png(path):
    """An 8-bit RGB or RGBA PNG (not interlaced), as written by the engine, as an Image."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit("figures.py: %s is not a PNG" % path)
    pos, idat, w, h, channels = 8, b"", 0, 0, 3
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in (2, 6) or interlace:
                sys.exit("figures.py: %s: only 8-bit RGB(A) PNGs without interlacing are read" % path)
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * channels
    img, prev = Image(w, h), bytearray(stride)
    for y in range(h):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        for x in range(w):
            img.px[3 * (y * w + x):3 * (y * w + x) + 3] = line[channels * x:channels * x + 3]
        prev = line
    return img


def read_pfm(path):
    """Returns (w, h, channels, rows top-down as lists of floats or of (r,g,b) tuples)."""
    data = open(path, "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        start = pos
        while not data[pos:pos + 1].isspace():
            pos += 1
        fields.append(data[start:pos].decode())
    pos += 1
    ch = 1 if fields[0] == "Pf" else 3
    w, h, scale = int(fields[1]), int(fields[2]), float(fields[3])
    fmt = ("<" if scale < 0 else ">") + "f" * (w * ch)
    rows = []
    for y in range(h):  # PFM rows are bottom-up
        vals = struct.unpack_from(fmt, data, pos + 4 * w * ch * y)
        rows.append(list(vals) if ch == 1 else [vals[3 * i:3 * i + 3] for i in range(w)])
    rows.reverse()
    return w, h, ch, rows


def grey(v):
    g = max(0, min(255, round(v * 255)))
    return (g, g, g)


def level0_from_view(path):
    """The linear-depth view at W×H shows level 0 (W/2×H/2) with every texel as a 2x2 block: undo that."""
    w, h, _, rows = read_pfm(path)
    return w // 2, h // 2, [rows[2 * y][0::2][: w // 2] for y in range(h // 2)]


def label(img, x, y, s, scale=2):
    img.rect(x - 3, y - 3, x + img.text_width(s, scale) + 3, y + 7 * scale + 3, (255, 255, 255))
    img.text(x, y, s, (0, 0, 0), scale)


# ---------------------------------------------------------------------------------------------
def depth_curve(out):
    """Stored depth D against view distance for near 0.35 and near 1 (far 1000)."""
    W, H = 640, 360
    img = Image(W, H)
    x0, y0, x1, y1 = 70, 20, 620, 310  # plot box (y grows down)
    dmax = 10.0

    def px(d):
        return x0 + (x1 - x0) * d / dmax

    def py(D):
        return y1 - (y1 - y0) * D

    def depth(d, n):
        A = -2 * FAR * n / (FAR - n)
        B = (FAR + n) / (FAR - n)
        return 0.5 * (B + A / d) + 0.5

    for k in range(0, 11, 1):
        img.line(px(k), y0, px(k), y1, (230, 230, 230))
    for k in range(0, 11):
        img.line(x0, py(k / 10), x1, py(k / 10), (230, 230, 230))
    img.line(x0, y1, x1, y1, (0, 0, 0))
    img.line(x0, y0, x0, y1, (0, 0, 0))
    for k in range(0, 11, 2):
        s = str(k)
        img.text(px(k) - img.text_width(s) / 2, y1 + 8, s)
    for k in (0, 2, 4, 6, 8, 10):
        s = "%.1f" % (k / 10)
        img.text(x0 - 10 - img.text_width(s), py(k / 10) - 7, s)
    img.text(x1 - img.text_width(words("distance")), y1 + 28, words("distance"))
    img.text(x0 + 10, y0 + 4, "D")

    for n, col in ((1.0, (150, 150, 150)), (NEAR, (30, 90, 200))):
        prev = None
        steps = 2000
        for i in range(steps + 1):
            d = n + (dmax - n) * i / steps
            p = (px(d), py(depth(d, n)))
            if prev:
                img.line(prev[0], prev[1], p[0], p[1], col, width=3)
            prev = p
    # D = 0.8 and 0.9 with near 0.35: 1.75 m and 3.49 m
    A = -2 * FAR * NEAR / (FAR - NEAR)
    B = (FAR + NEAR) / (FAR - NEAR)
    for D in (0.8, 0.9):
        d = A / ((2 * D - 1) - B)
        img.line(x0, py(D), px(d), py(D), (200, 60, 40), dash=4)
        img.line(px(d), py(D), px(d), y1, (200, 60, 40), dash=4)
        img.disc(px(d), py(D), 4, (200, 60, 40))
        img.text(px(d) + 6, y1 - 20, "%.2f" % d, (200, 60, 40))
    label(img, 330, 200, "near 0.35", 2)
    img.rect(310, 205, 324, 209, (30, 90, 200))
    label(img, 330, 225, "near 1", 2)
    img.rect(310, 230, 324, 234, (150, 150, 150))
    img.save(out)


def spiral(out):
    """The 11 sample taps of sao.frag for two spiral-turn counts, coloured by the mip level they read."""
    W, H = 640, 340
    img = Image(W, H)
    colours = [(30, 90, 200), (40, 160, 90), (230, 150, 30), (200, 50, 50)]
    n, pixels, log_mip_offset, max_mip = 11, 100.0, 3, 3
    for panel, turns in enumerate((3, 7)):
        cx, cy, R = 160 + 320 * panel, 160, 125
        img.circle(cx, cy, R, (160, 160, 160), dash=3)
        img.line(cx - 5, cy, cx + 5, cy, (0, 0, 0))
        img.line(cx, cy - 5, cx, cy + 5, (0, 0, 0))
        start = 0.0
        prev = None
        for k in range(401):  # the continuous spiral the taps sit on
            r = k / 400
            a = r * turns * 2 * math.pi + start
            p = (cx + R * r * math.cos(a), cy - R * r * math.sin(a))
            if prev:
                img.line(prev[0], prev[1], p[0], p[1], (215, 215, 215))
            prev = p
        for i in range(n):
            ratio = (i + 0.5) / n
            a = ratio * turns * 2 * math.pi + start
            dist = int(ratio * pixels)
            msb = dist.bit_length() - 1 if dist > 0 else -1
            level = min(max(msb - log_mip_offset, 0), max_mip)
            x, y = cx + R * ratio * math.cos(a), cy - R * ratio * math.sin(a)
            img.disc(x, y, 7, colours[level])
            s = str(i)
            img.text(x + 8, y - 16, s, (0, 0, 0), 2)
        t = words("turns") % turns
        img.text(cx - img.text_width(t) / 2, 298, t)
    x = 40
    for level, c in enumerate(colours):
        img.disc(x, 327, 6, c)
        img.text(x + 12, 320, words("level") % level, (0, 0, 0), 2)
        x += 150
    img.save(out)


def mip_chain(pfm, out):
    """Levels 0-3 of the linear-depth texture (min of 2x2 per level), each shown at 320x180."""
    w, h, lv = level0_from_view(pfm)
    levels = [(w, h, lv)]
    for _ in range(3):
        pw, ph, p = levels[-1]
        nw, nh = max(pw // 2, 1), max(ph // 2, 1)
        levels.append((nw, nh, [[min(p[min(2 * y + dy, ph - 1)][min(2 * x + dx, pw - 1)] for dy in (0, 1) for dx in (0, 1))
                                 for x in range(nw)] for y in range(nh)]))
    scale = 1.0 / max(v for row in lv for v in row if v < FAR)
    img = Image(640, 360)
    for i, (lw, lh, p) in enumerate(levels):
        ox, oy = 320 * (i % 2), 180 * (i // 2)
        for y in range(180):
            row = p[y * lh // 180]
            for x in range(320):
                img.set(ox + x, oy + y, grey(row[x * lw // 320] * scale))
        label(img, ox + 6, oy + 6, words("level-size") % (i, lw, lh))
    img.line(320, 0, 320, 359, (255, 0, 0))
    img.line(0, 180, 639, 180, (255, 0, 0))
    img.save(out)


def course_depth(pfm, out):
    """What the course's debug draw shows: R32F linear depth through simple.frag (red only), at 3 scales."""
    w, h, lv = level0_from_view(pfm)
    pw, ph = 213, 120
    img = Image(3 * pw + 1, ph)
    for panel, (k, text) in enumerate(((1.0, "x 1"), (0.01, "x 0.01"), (0.05, "x 0.05"))):
        for y in range(ph):
            row = lv[y * h // ph]
            for x in range(pw):
                r = max(0, min(255, round(row[x * w // pw] * k * 255)))
                img.set(panel * pw + x, y, (r, 0, 0))
        label(img, panel * pw + 6, 6, text)
        if panel:
            img.line(panel * pw, 0, panel * pw, ph - 1, (255, 255, 255))
    img.save(out)


def normals(pfm, out):
    """View-space normals as sao.frag reconstructs them (quad derivatives of positions), on the CPU."""
    w, h, lv = level0_from_view(pfm)
    fov_scale = 1 / math.tan(math.radians(FOV_Y) / 2)
    ndc_to_view = (w / h / fov_scale, 1 / fov_scale)

    def pos(x, y):  # y is top-down here; texture v is bottom-up
        d = lv[y][x]
        u, v = (x + 0.5) / w, 1 - (y + 0.5) / h
        return ((2 * u - 1) * ndc_to_view[0] * d, (2 * v - 1) * ndc_to_view[1] * d, -d)

    img = Image(w, h)
    for y in range(h):
        ya = y - (y % 2)  # the 2x2 quad: rows ya (top) and ya+1
        for x in range(w):
            d = lv[y][x]
            if d >= FAR:
                img.set(x, y, (90, 90, 90))
                continue
            xa = x - (x % 2)
            p, px1 = pos(xa, y), pos(min(xa + 1, w - 1), y)
            dpdx = [px1[i] - p[i] for i in range(3)]
            # dFdy points up the screen: from the lower row of the quad to the upper one
            q0, q1 = pos(x, min(ya + 1, h - 1)), pos(x, ya)
            dpdy = [q1[i] - q0[i] for i in range(3)]
            c = (dpdx[1] * dpdy[2] - dpdx[2] * dpdy[1], dpdx[2] * dpdy[0] - dpdx[0] * dpdy[2], dpdx[0] * dpdy[1] - dpdx[1] * dpdy[0])
            l2 = sum(v * v for v in c)
            on_edge = max(abs(dpdx[2]), abs(dpdy[2])) > 0.1 * d
            if l2 <= 1e-30 or on_edge:
                img.set(x, y, (0, 0, 0))
                continue
            l = math.sqrt(l2)
            img.set(x, y, tuple(max(0, min(255, round((v / l * 0.5 + 0.5) * 255))) for v in c))
    img.save(out)


def grid(out, cw, ch, items):
    """Crops of cw x ch from single-channel PFMs, 2 per row, labelled. Item: LABEL=FILE@X,Y."""
    rows = (len(items) + 1) // 2
    img = Image(2 * cw, rows * ch)
    for i, item in enumerate(items):
        name, rest = item.split("=", 1)
        path, xy = rest.rsplit("@", 1)
        x0, y0 = (int(v) for v in xy.split(","))
        w, h, chn, data = read_pfm(path)
        ox, oy = cw * (i % 2), ch * (i // 2)
        for y in range(ch):
            for x in range(cw):
                v = data[y0 + y][x0 + x]
                img.set(ox + x, oy + y, grey(v) if chn == 1 else tuple(grey(c)[0] for c in v))
        label(img, ox + 6, oy + 6, name)
    img.line(cw, 0, cw, img.h - 1, (255, 0, 0))
    for j in range(1, rows):
        img.line(0, ch * j, img.w - 1, ch * j, (255, 0, 0))
    img.save(out)


def scale_label(v):
    """A number as the engine's scale bar writes it: 3 significant digits, trailing zeros dropped."""
    a = abs(v)
    if a == 0:
        return "0"
    if not 0.001 <= a < 10000:
        return "%.1e" % v
    text = "%.*f" % (max(0, 2 - math.floor(math.log10(a))), v)
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return ("+" if v > 0 else "") + text


def error_legend(png, pfm, out, value_range):
    """The engine's error map with the words of its scale (`io/scale_bar.rs`) redrawn in LANG: the map
    and the colour bar stay as the engine drew them. The scale sits below the map: 6 rows, the
    marker's label (10 rows), 2 rows, the marker (5), 1 row, the bar (14), 3 rows, the ticks' labels."""
    img = read_png(png)
    w, h, _, rows = read_pfm(pfm)
    top = h * img.w // w  # maps narrower than 320 pixels are enlarged by a whole factor
    if img.h != top + 57:
        sys.exit("figures.py: %s is not an error map of %s (%d rows, expected %d)" % (png, pfm, img.h, top + 57))
    worst = max((v for row in rows for v in row), key=abs)
    bg = tuple(img.px[3 * (top + 1) * img.w:3 * (top + 1) * img.w + 3])
    fg = (235, 235, 235)
    marker_row = top + 6 + 10 + 2
    lit = [x for x in range(img.w) if tuple(img.px[3 * (marker_row * img.w + x):3 * (marker_row * img.w + x) + 3]) == fg]
    marker_x = (lit[0] + lit[-1]) // 2 if lit else img.w // 2
    img.rect(0, top, img.w, marker_row, bg)
    img.rect(0, marker_row + 5 + 1 + 14, img.w, img.h, bg)
    text = words("max") % scale_label(worst)
    x = max(8, min(img.w - 8 - img.text_width(text), marker_x - img.text_width(text) // 2))
    img.text(x, top + 2, text, fg)
    ticks_y = marker_row + 5 + 1 + 14 + 3
    left = words("too-dark") % scale_label(-value_range)
    right = words("too-light") % scale_label(value_range)
    img.text(8, ticks_y, left, fg)
    img.text(img.w // 2 - img.text_width("0") // 2, ticks_y, "0", fg)
    img.text(img.w - 8 - img.text_width(right), ticks_y, right, fg)
    img.save(out)


def main(argv):
    global LANG
    if len(argv) > 2 and argv[1] == "--lang":
        if argv[2] not in ("en", "ja"):
            sys.exit("figures.py: --lang takes en or ja, not %r" % argv[2])
        LANG = argv[2]
        argv = argv[:1] + argv[3:]
    cmd = argv[1] if len(argv) > 1 else ""
    if cmd == "depth-curve":
        depth_curve(argv[2])
    elif cmd == "spiral":
        spiral(argv[2])
    elif cmd == "mip-chain":
        mip_chain(argv[2], argv[3])
    elif cmd == "course-depth":
        course_depth(argv[2], argv[3])
    elif cmd == "normals":
        normals(argv[2], argv[3])
    elif cmd == "grid":
        grid(argv[2], int(argv[3]), int(argv[4]), argv[5:])
    elif cmd == "error-legend":
        error_legend(argv[2], argv[3], argv[4], float(argv[5]) if len(argv) > 5 else 0.25)
    elif cmd == "glyphs":
        glyph_lines(argv[2:-1], argv[-1])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
