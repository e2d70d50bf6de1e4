"""The wheel bundles libspectral.so, native code for the building machine: tag it for this platform, not pure Python."""
from setuptools import setup
from setuptools.dist import Distribution


class BinaryDistribution(Distribution):
    def has_ext_modules(self):
        return True


try:
    from wheel.bdist_wheel import bdist_wheel

    class PlatformWheel(bdist_wheel):
        """A py3-none-<platform> wheel: the package is pure Python over ctypes, the library is for one platform."""

        def get_tag(self):
            _, _, plat = super().get_tag()
            return "py3", "none", plat

    cmdclass = {"bdist_wheel": PlatformWheel}
except ImportError:
    cmdclass = {}

setup(distclass=BinaryDistribution, cmdclass=cmdclass)
