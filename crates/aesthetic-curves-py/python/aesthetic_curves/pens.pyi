from typing import Any, Optional, Sequence

from fontTools.pens.basePen import BasePen  # type: ignore[import-untyped]

__all__ = ["CheckPen", "fix_glyph"]

class CheckPen(BasePen):  # type: ignore[misc]
    contours: list[tuple[list[list[tuple[float, float]]], bool]]
    def __init__(self, glyphSet: Optional[Any] = None) -> None: ...
    def check(
        self,
        grid: float = 0.0,
        g1_angle: float = 0.05,
        g2_jump: float = 0.05,
        near_break: float = 3.0,
        min_bump: float = 0.05,
    ) -> dict[str, Any]: ...

def fix_glyph(
    glyph: Any, tolerance: float = 2.0, grid: float = 1.0, bumps: bool = True
) -> list[dict[str, Any]]: ...
