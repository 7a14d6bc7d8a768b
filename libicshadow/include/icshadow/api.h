/* icshadow/api.h — ICS_API marks every public declaration of libicshadow and
 * libicshadow_render. The libraries are built with hidden visibility by default, so only what
 * carries ICS_API is exported from the shared objects (tests/export check compares the exported
 * symbols with the declarations in the public headers). */
#ifndef ICSHADOW_API_H
#define ICSHADOW_API_H

#if defined(_WIN32) && defined(ICS_BUILDING_SHARED)
#define ICS_API __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#define ICS_API __attribute__((visibility("default")))
#else
#define ICS_API
#endif

#endif
