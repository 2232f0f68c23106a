/* version.h - endosim's release, shown by every program and in status. */
#ifndef ENDOSIM_VERSION_H
#define ENDOSIM_VERSION_H

#define ENDOSIM_VERSION "0.1.0"

#endif
