# Copies a generated stub IN to OUT with its imports of sibling stubs (`from sph.v1 import`)
# pointed at the package they are staged in (`from sphd.proto import`).
file(READ ${IN} text)
string(REPLACE "from sph.v1 import" "from sphd.proto import" text "${text}")
file(WRITE ${OUT} "${text}")
