// One #version per loader, chosen by the loader's macros: Iris's preprocessor resolves this
// before the driver reads the text, so the driver sees one #version, first, and the loader's
// macros after it (a driver reading this text as it stands would not know MC_VERSION here).
#ifdef MC_VERSION
    #version 330 compatibility
#else
    #version 120
#endif
