from typing import Any

REPORTED: dict[str, float]
LISTED: int
PROFILE: dict[str, Any]
check_curvature: Any
