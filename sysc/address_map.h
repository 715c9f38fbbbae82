// The device's address map moved to ref/ (ref/address_map.h: the device contract's, which the host's sysc backends
// and the AXI top speak too); its names are still voxcd::sysc's. This header stays for initiators that include it
// from here.
#pragma once

#include "voxcd/ref/address_map.h"
