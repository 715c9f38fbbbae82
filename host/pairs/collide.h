// Pair tests on a device, in one include: the device image (pairs/image.h), the collider (pairs/collider.h) and the
// contacts (pairs/contact.h, pairs/contacts.h).
#pragma once

#include "voxcd/host/pairs/collider.h"
#include "voxcd/host/pairs/contact.h"
#include "voxcd/host/pairs/contacts.h"
#include "voxcd/host/pairs/image.h"
