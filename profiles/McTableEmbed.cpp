// The shipped mc-table (profiles/data/mc_table.bin) compiled into the library as bytes:
// the assembler's .incbin copies the file into .rodata between two symbols, so the data
// needs no file at run time and no generated source. CMake passes the file's absolute
// path as SSS_MC_TABLE_PATH and lists the file as a dependency of this object, so a
// regenerated table rebuilds the library.
#if !defined(__ELF__) || !(defined(__x86_64__) || defined(__aarch64__))
#error "McTableEmbed.cpp's assembly is written for ELF on x86-64/AArch64 (symbol names, @object)"
#endif
#ifndef SSS_MC_TABLE_PATH
#error "SSS_MC_TABLE_PATH must name profiles/data/mc_table.bin (set by profiles/CMakeLists.txt)"
#endif
#ifndef SSS_MC_TABLE_G_PATH
#error "SSS_MC_TABLE_G_PATH must name profiles/data/mc_table_g.bin (set by profiles/CMakeLists.txt)"
#endif

__asm__(
    ".pushsection .rodata\n"
    ".balign 16\n"
    ".globl sss_mc_table_begin\n"
    ".hidden sss_mc_table_begin\n"
    ".type sss_mc_table_begin, @object\n"
    "sss_mc_table_begin:\n"
    ".incbin \"" SSS_MC_TABLE_PATH "\"\n"
    "sss_mc_table_end:\n"
    ".balign 8\n"
    ".globl sss_mc_table_size\n"
    ".hidden sss_mc_table_size\n"
    ".type sss_mc_table_size, @object\n"
    "sss_mc_table_size:\n"
    ".8byte sss_mc_table_end - sss_mc_table_begin\n"
    // The anisotropic layers (issue 18 part 4), the same way.
    ".balign 16\n"
    ".globl sss_mc_table_g_begin\n"
    ".hidden sss_mc_table_g_begin\n"
    ".type sss_mc_table_g_begin, @object\n"
    "sss_mc_table_g_begin:\n"
    ".incbin \"" SSS_MC_TABLE_G_PATH "\"\n"
    "sss_mc_table_g_end:\n"
    ".balign 8\n"
    ".globl sss_mc_table_g_size\n"
    ".hidden sss_mc_table_g_size\n"
    ".type sss_mc_table_g_size, @object\n"
    "sss_mc_table_g_size:\n"
    ".8byte sss_mc_table_g_end - sss_mc_table_g_begin\n"
    ".popsection\n");
