#pragma sao effect bad version=1
// A device never ends (/dev/zero has no newline to stop getline): only regular files are read.
#include "/dev/zero"
#pragma sao resource src kind=input format=depth "in"
