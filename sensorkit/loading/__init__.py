"""Loading robot descriptions: strict XML, package resolution and xacro expansion."""

from sensorkit.loading.document import Document, LoadResult, load_description
from sensorkit.loading.packages import PackageResolver

__all__ = ["Document", "LoadResult", "PackageResolver", "load_description"]
