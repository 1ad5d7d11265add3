"""What Prism renders differently from Cycles for one UDIM image, gathered while its tiles are read and
then said once per kind, naming the image and its tiles and what Prism renders instead."""

from __future__ import annotations

from collections import defaultdict

from .colour_spaces import RAW_SPACES, is_data

_PATTERNS = {"UV_GRID": "UV Grid", "COLOR_GRID": "Color Grid"}


def _tiles(numbers):
    """'tile 1002' or 'tiles 1002, 1011'."""
    return f"tile{'s' if len(numbers) > 1 else ''} {', '.join(str(n) for n in numbers)}"


def _it(numbers):
    return "them" if len(numbers) > 1 else "it"


class UdimWarnings:
    """The warnings of UDIM image ``image``, noted tile by tile (``unread``, ``pattern``, ``check_tile``)
    and for the whole image (``check_image``), said by ``emit``."""

    def __init__(self, image):
        self.name = image.name
        self.colour_space = image.colorspace_settings.name
        # Cycles reads the tiles through Blender when any is packed or generated, and then reads them all
        # as the first tile's kind: 8-bit there makes it decode float tiles in the colour space as well.
        self.read_through_blender = bool(image.packed_files) or any(t.is_generated_tile for t in image.tiles)
        self.first_number = min(tile.number for tile in image.tiles)
        self.first_is_float = False  # as Blender answers for a first tile it cannot read
        self.unread_tiles = defaultdict(list)
        self.pattern_tiles = defaultdict(list)
        self.float_tiles = []
        self.image_messages = []

    def check_image(self, image, packed):
        """Notes what concerns the whole image: packed files Blender ignores, unsaved changes."""
        if len(image.packed_files) and packed is None:
            count, tiles = len(image.packed_files), len(image.tiles)
            self.image_messages.append(
                f"reads the UDIM image '{self.name}' from its files: it has {count} packed "
                f"file{'s' if count > 1 else ''} for {tiles} tile{'s' if tiles > 1 else ''}, and Blender (so "
                "Cycles) ignores packed tiles unless every tile is packed, dropping them when it next loads a tile.")
        if image.is_dirty:
            self.image_messages.append(
                f"cannot read the unsaved changes of the UDIM image '{self.name}' (painted or edited in Blender), "
                "which Cycles renders: Prism renders each tile as saved, packed or generated. Save the image, or "
                "pack it (Image ▸ Pack), to render the changes.")

    def unread(self, number, reason):
        self.unread_tiles[reason].append(number)

    def pattern(self, number, generated_type):
        self.pattern_tiles[generated_type].append(number)

    def check_tile(self, number, source):
        """Notes a tile read: float tiles that Cycles decodes in the image's colour space."""
        if number == self.first_number:  # tiles are read in order, the first one first
            self.first_is_float = source.is_float
        decodes = self.colour_space not in RAW_SPACES and not is_data(self.colour_space)
        if source.is_float and decodes and self.read_through_blender and not self.first_is_float:
            self.float_tiles.append(number)

    def emit(self, say):
        """Says each warning with ``say(message)``."""
        for message in self.image_messages:
            say(message)
        for reason, numbers in self.unread_tiles.items():
            say(f"cannot read {_tiles(numbers)} of the UDIM image '{self.name}' ({reason}); Prism renders "
                f"{_it(numbers)} magenta, as Cycles renders a missing tile.")
        for generated_type, numbers in self.pattern_tiles.items():
            pattern = _PATTERNS.get(generated_type, generated_type)
            say(f"does not draw the generated {pattern} of {_tiles(numbers)} of the UDIM image '{self.name}'; "
                f"Prism renders {_it(numbers)} magenta (Image ▸ Save As writes the tiles to files Prism reads).")
        if self.float_tiles:
            numbers = self.float_tiles
            say(f"renders the float pixels of {_tiles(numbers)} of the UDIM image '{self.name}' as scene-linear, "
                f"as Blender holds them; Cycles 4.5 decodes them from '{self.colour_space}' again (the image's "
                "first tile is 8-bit), which darkens them.")
