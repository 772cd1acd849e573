"""lavapipe.py - where lavapipe's Vulkan driver file lies.

lvp_icd.x86_64.json up to Mesa 24 (Debian 12), lvp_icd.json from Mesa 25
(bookworm-backports, Debian 13); the bench scripts name it so that tp2
renders on lavapipe whatever else the loader finds.
"""
import os

_DIR = '/usr/share/vulkan/icd.d'
ICD = next((path for path in (os.path.join(_DIR, 'lvp_icd.x86_64.json'),
                              os.path.join(_DIR, 'lvp_icd.json'))
            if os.path.exists(path)),
           os.path.join(_DIR, 'lvp_icd.x86_64.json'))
