/* autobal/export.h: symbol visibility for the public API. */
#ifndef AUTOBAL_EXPORT_H
#define AUTOBAL_EXPORT_H

#if defined(AUTOBAL_BUILDING) && defined(__GNUC__)
#define AUTOBAL_API __attribute__((visibility("default")))
#else
#define AUTOBAL_API
#endif

#ifdef __cplusplus
#define AUTOBAL_BEGIN_DECLS extern "C" {
#define AUTOBAL_END_DECLS }
#else
#define AUTOBAL_BEGIN_DECLS
#define AUTOBAL_END_DECLS
#endif

#endif
