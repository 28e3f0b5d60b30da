"""Measured results of the x86 ``rsqrtps`` instruction, for Eigen's fast float square root.

Eigen 3.4 (``EIGEN_FAST_MATH``, on by default) computes ``cwiseSqrt()`` of float packets on
SSE as ``x * r``, ``r`` one Newton step from ``_mm_rsqrt_ps(x)`` (see
:func:`navfn_smt.nav2.inflation.eigen_sse_sqrt`).  ``rsqrtps`` is a table lookup whose
contents differ between CPU vendors.  On the machine measured here (an AMD EPYC, Zen) its
result for a positive normal float depends only on the exponent's parity and the top 12
mantissa bits, and scales exactly by powers of 4 (checked for every mantissa, exponents
-60..60, and end to end on every integer 0..2^24).

``AMD_ZEN``: 8192 float32, entry ``p * 4096 + i`` = ``rsqrtps`` of the float with biased
exponent ``127 + p`` and mantissa ``i << 11`` (inputs in [1, 2) for p = 0, [2, 4) for p = 1).
Measured with a small C program calling ``_mm_rsqrt_ps`` (gcc 12, Debian 12).

``INTEL_XEON_6_167``: the same table measured on an Intel Xeon (CPU family 6, model 167), the
machine the live costmap difftest first ran on; the same structure holds there (checked for
every mantissa at every tenth exponent of -60..60 and every eighth elsewhere), and Eigen's
square root built from Nav2's layers' flags equals the emulation on every integer below 2^20.
"""

import base64
import zlib
from functools import lru_cache

import numpy as np

_AMD_ZEN = (
    "eNp10DfUtmy3lWHMmDFjZhsxY8a4UbeKGTNmzJgxY6akpKSkpKSkpKSkpKSkpKR0vuM+x3jWd43/LY56nXN57//7ce+RWy45"
    "5ZBdNqyyyCyTjDJIL600UkslpRSSS4ZUEoklklAC8eX9v7ovt1xyyiG7bFhlkVkmGWWQXjpppZFaKimlkByZpJJILJGEEogn"
    "7/9Rg9xyySmH7NhklUVmmWSUQTpppZFaKimlkByZpJJILJGEEogvnrz/Ww1yyyWnHNhlk1UWmWWSUQbppZNWGqmlkhKF5JJJ"
    "KonEEkkgvnjy/i81yC2XnDhkl01WWWSWSUYZpJdOWmmklgqlFJJLJqkkEkskoQTiiyfv/1SH3LjklEN22WSVRWaZZJRBeumk"
    "lQa1VFJKIblkkkoisUQSSiC+ePL+j49HbrnklEN22WSVRWaZZJRBeunQSiO1VFJKIblkkkoisUQSSiA+vG8drTrklktOObDL"
    "JqssMsskIwbppZNWGqmlklIKySVDKonEEkkogfjw5P3v6pFLTjlkxyarLDLLJKMM6KWTVhqppZISheSSSSqJxBIhlEB8ef+b"
    "OuSWC6ccsssmqywyY5JRBumlk1Ya1FJJKYXkkkmKRGKJJJRAfPHw/lc1yS2XnHLIjk1WWWSWSUYZ0EsnrTRSSyUlCsklk1QS"
    "iSVCKIH44sn7X9QjNy455ZBdNlllwSyTjDJIL520aKSWSkopJJcMqSQSSyShBOLDk/c/q0luueSUA7tsssois0wyYpBeOmml"
    "kVoqlFJILpmkkkiMSEIJxBdP3v+kHtxyySmH7LLJikVmmTDKID06aaWRWioppUAumaSSSCyRhAjEF0/e/6gmueXCKYfs2GSV"
    "BbNMMsogvXTSopFaKimlkByZpJJIjEhCCcQXD2+jNrnlwimH7LJhlUVmmWTEIJ200qCWSkopkEsmqSQSI5JQAvHhyfsf1CU3"
    "LjnlkF02rLLILBNGGaSXDq00UkslJQrJJZMUicQSSYhAfPHk/fdqwy2XnHJgl01WWTDLJKMM0qOTVhqpUUkpheTIJJVEYokQ"
    "SiC+eHj/ndrklgunHLLLJisWmWWSEYP00kmLRmqppJQCOTJJkUgskYQIxBdP3n+rPtxyySkHdtlklQWzTDLKID06aaWRGpWU"
    "UkiOTFJJJJYIIQLx4cn7b9QnNy455ZBdNqyyyCwTRhmklw6tNFJLJSUK5JIhlURiiRBKIL548v7rj0duueTEITs2WWXBLJOM"
    "GKSXTlo0UqOSUgrkkkmKRCIJJYAvHt5/pUa5cckpB3bZZJUFs0wYZZAenbTSoJZKSimQS4ZUEokRSSgBfPHkrdWJWy6ccsiO"
    "TVZZMMskowzopUMrjdSopJQCuWSSSoJYIoQSiA9P3n+pTtxyySkHdtmwyiIzJhllQC+dtNKglgqlFJIjk1QSxIgkRCA+PHn/"
    "hVpxyyUnDtllkxWLzJhklAG9dNKikVoqKVFIjkxSSRBLJCEC+OLh/edqxS2XnDhklw2rLDLLhFEG9NJJi0ZqqVCikByZpEgk"
    "lgihBOLD+9b5zz5uuXDKITs2WbHIjElGDNKjk1Ya1FKhlAK5ZEglQSyRhAjEhyfvP/145MIpB3bZZMUiMyYZMUiPTlo0UkuF"
    "UgrkkiGVBLFECCUQH9633n/y8ciNS04csmOTVRbMMmGUAb10aKVBLZWUKCRHJikSiRFJiEB88fD+Y3XjlgunHNhlwyqLzJhk"
    "xCA9OmnRSI1KSimQS4ZUEsQSIZQAvnjyVh+P3LjkxCE7NlmxyCwTRhnQS4dWGtRSoZRCcmSSIpEYkRFKAF+8b+3/6OORG5ec"
    "OGTHJisWmWXCKAN66dBKIzUqKVFIjgypJIglQohAfHjf2v/hx4NbLpxyyC4bVlkwy4QRg/TopEWDWiqUUiBHJikSiSWSEIH4"
    "8L61/4OPB7dcOOXAjk1WLDJjwigDeumklQa1VCilQI5MUiQSI0IoAXzx8P79j0duXHLiwC4bVlkwY5IRg/To0EqDWiqUKCRH"
    "JqkkEiOSEIH48PD+PW3ALRdOHLJjkxULZpkwyoAenbRopEaFUgrkkiFFIjEiCRHAFw/v39UO3LjkxCE7NqyyYJYJIwbp0UmL"
    "BrVUKKUwcsmQIkEsEUIJ4IuH9+9oC25cOOXALhtWWTDLhBEDeunQSoNaKpRSIEeGVBLEEiGUAL54eMuPB7dcOOXAbmyyYsGM"
    "SUYM0qOTFo3UqFCikByZpEgkRiQhAvjwvu352x+P3LiMUw7s2LDKglkmjDKglw4tGtRSoZQCuZFJigQxIgkRiA/v26a/9fHI"
    "jQsnDtmxyYrFmGXCiAG9dGilQS0VSimQI0MqCWKJEBqB+PDw/s2PR25ccuIwdtmwYsEsE0YZ0EuHFg1qqVCiQC4ZUiSIEUmI"
    "AD68b7v+xseDGxdOObBjwyoLJowY0EuHFg1qqVCiQI5MUiSIEUmIAD48vH9du3DjwikHdmxYsciMCSMG6dGhRYNaKpQokEuG"
    "FAliRBIigA9P3r/28eDGhVMO7NiwyoIZE0YM0qNDi0ZqVChRIJcMKRLEEiFEAB/et31/9ePBjUtOx4Edm6xYMGOSEQN6dGil"
    "QY0KpRTIkSFFIjEihAjENzy8xceDGxdOHNhlkxULZkwYMaBHJ600qFGhRIEcGVIkiBEhRAAfHt6/op1y48KJAzs2rFgwY8KI"
    "AT06tGiklgolCuTIkCJBjAghAvjw8P7ljwe3XHLiwI4NKxbMmDBiQI8OLRrUqKSUAjkypEgQI0KIAD48vH/p48GNCycO7Niw"
    "YsGMCaMM0qNDiwY1KpQokCNDigQxIoQI4MPD+xc/Hty4cOKQHRtWLJgxYcSAHh1aNKhRoUSBHBlSJIgRIUQAHx7ev/Dx4MaF"
    "Ewd2bFixYMaEEQN6dGjRoEaFEgVyZEiRIEaEEAF8eHj//MeDGxdOHNixYcWCGRNGDOjRoUWDGhVKFMiRIUWCGBFCBPDh4f1z"
    "Hw9uXDhxYMeGFQtmTBgxOHp0aNGgRoUSBXJkSJEgRoQQAXx4ePOPBzcunDiwY8NqLJgxYZQBPTq0RoMaFUqjQI7MSJEgRiQh"
    "AvjwjPfPfjy4ccmJAzs2Y8WCGZMxYkBvdGjRoJYKJQrkRoYUCWIjQojA8OHh/TMfj9y4cOIwdmxYsRgzJozGgB4dWmlQo0Jp"
    "FMiRITUSxIiMEAF8eN/+8Kc/Hty4jBMHdmzGigWzMWHEgN7o0KIxalQoUUiODCkSI0aEEAF8eMb7Ex8PblzGiQO7sWHFgtmY"
    "MGIwenRo0Rg1KpRGgRwZUiORWCKERgAfHt4/9eXBjcs4cWDHZqxYMBsTRgzojQ4tGqNGhRKFkSNDaiSIESE0AvjwjPdPfjy4"
    "cRknDuzGhhULZmPCiMHo0aFFY9SoUBoFcmRIjQQxIiNEAB+e8f6Jjwe3ceHEgd3YsGIxZkwYMRi9dGiNBrVRoUSBHJmRIjFi"
    "RAgRwDc8vNmXBzcux2kc2I0NKxbMmIwRg9GjQ4sGtVGhNArkyJAiMWJERogAPjy8P/7lwW1cOHE4dmPDaiyYMWHEYPTojBYN"
    "alQojQK5kSFF4oiNCKERwIeH949/PMaNyzhxYMeG1VgwGxNGDI7e6NAaDWpUKFEYOTIjRYLYESE0AviGZ7x/TP/Cjcs4cRi7"
    "sRkrFmPGZIzGID06tEaD2qiM0iiQGxlSIzFiiRAiMHx4xvtHvzzGjcs4cRi7scmKBbMxYTQGozc6tEaD2qiM0iiQGxlSIzFi"
    "iRAiMHx4xvtHvjzGjcs4cRi7sRkrFmPGZIzGID06tEaD2qiM0iiQGxlSIzFiI0JoBPANz3j/sH6H27hwGgd2YzNWY8FsTBiN"
    "weiNDq3RoDYqozQK5EaG1EiM2IgQGgF8wzPeP/TlwW1cOI3D2I0Nq7FgNiYZMRg9OqNFY9RGZZQojByZkRqJESMyQgSGb3jG"
    "m348xo3LOI3D2LEZKxZjNiZjxGD06IzWaIwalVGiMHIjM1IkRozICI3A8OEZ7x/8eIzbcRknDmM3NqzGYsyYjNEY0Bud0aIx"
    "aqNCaRRGjsxIjQSxERkhAsM3vB/h/QNfHtzGZZw4jN3YsBqLMWMyRmNAb3RGi8aojQqlURg5MiM1EsRGZIQ/QmD48Iz39395"
    "cBuXceIwdmPDaizGjMkYjQG90RktGqM2qh+hNArkRmakSIzYiBAageHD+/bP3/fxyI1LThyyY5MVi8wyYZQBvXRopUEtFUop"
    "JEcmKRKJEUmIQHx435p/r3pxyYlDdmyyYpEZk4wyoJcOrTSopUIpBXJkSCVBLBFCCeCLh/f3qF9uXHLikB2brFhkxiSjDOil"
    "QysNaqlQSoFcMkmRSIxIQgTiw5P3d388csuFUw7ssmGVBbNMGDGglw6tNKilQikFcskkRSIxIgkRiA/vW3vy8cgtF045sMuG"
    "VRbMMmHEgF46tNKglgqlFMglkxSJxIgkRCA+vG/tv+vjwY1LThyyY5MVi8yYZMQgPTq00qCWCqUUyJFJigSxRAglgC8e3t/5"
    "8ciNC6cc2GXDKgsmjDKgRyctGqlRSYkCuWRIkUiMSEIE4sPD+zu0ATcuOXHIjk1WLJhlwohBenTSopEaFUopkCOTFInEiCRE"
    "AF88vL/945Ebl5w4ZHdssmLBLBNGGdBLhxaN1KhQSoFcMqSSIEYkIQL44uH9bdqDWy6cOGTHhlUWzDJhlMHRS4cWjdSopEQh"
    "OTKkkiBGJCEC8eHJ+1t/6JEbF045sMuGVRbMmGTEgB6dtGhQo0QhOTKkSCRGhBABfPHw/paPB7dcOHFgxyYrFsyYZMSAHi0a"
    "qVGhRCE5MqRIEEuEEAF88fDGHw9uXHLiwI5NViyYMWGUAT06tNKgRoUSheTIkCKRGBFCBPDFw/ubPx7ccuHEgR2brFgwY5IR"
    "A3p0aKVBjQqlFMiRIUUiMSKECMSHh/c3fTy45cKJA7tsWLFgxiQjBvTopEWDGhVKKZAjQyoJYkQIEYgPD+9v/Hhw48JpHLJj"
    "w4oFMyaMMqCXDi0a1KhQopAcmaRIECNCiAC+4X3b+hs+Hty4cOLALhtWWTBjwogBPTqjlQY1KpQokCOTFInEiBAigA8P76//"
    "8siNCycO7NiwGovMmDBiQI8OrTSopUKJAjkypEiMWCKECODDw/vrPh7jlgsnDuzYsGKRGZOMGNCjQ4sGtVFJiQI5MqRIEBuR"
    "hAjgw8P7Yx8PbuPCiQM7NqxYMGPCiAE9OrRoUKNCiQI5MqRIECNCiAA+PLzRx4MbF04c2LFhxYIZE0YM6NGhRYMaFUoUyJEh"
    "RYIYEUIE8OHh/bUfD25cOHFgx4YVC2ZMGDGgR4cWjaNGhRIFcmRIkSBGhBABfHh4f83HgxsXThzYsWF1LJgxYcSAHh1aNKhR"
    "oUSBHJkjRYIYEUIE8OF9+8Ov/vLgxoUTh7FjM1YsmDFhNAbppTNaNKhRoTQK5EaGFAliREYogfiGh/dXfTy4cRknDmPHhhUL"
    "ZmPCaAzo0aFFY9RSSWkUyJEhRWLEiIwQAXx4eH/llwe3ceHEgR2bsWIxZkwYMaA3OmmlMWpUKFEgNzKkRoIYEUIEhg/PeH/F"
    "x4MbF07jwG5sWLFgxmSMGIweHVo0qI3KKFEYOTKkRoIYEUIjgA/PeH/5x4Mbl3HiwG5sWLFgNiaMGIweHVo0Ro0KpVEgR4bU"
    "SBAjMkIE8OEZb/jx4DYunDiwGxtWLMbsmDAaA3p0RosGNSqjRIHcyJAiQWxECBEYPjy8v+zjMW5cOI3DsWMzViyYjQkjBvRG"
    "hxaNUaNCicLIkSE1EkeMyAgRwDc8vL/048FtXDiNA7tjw2osmI0JIwb06IwWjVGjcpQojByZkSJBjAihEcA3PLy/5Ice3MaF"
    "0ziwY8OKxZgxGSMGR4/OaNEYNSpHicLIkRkpEsSIEBoBfMPD+4t/6MFtXDiNA7tjw2osmI0JIwb06IwWjVGjcpQojByZkSJx"
    "xIiMEIHhw3O8v+jjMW5cxokDu7FhNRZjxmSMxoDe6IwWjVEbFUqjMHJkRmokiI3ICBEYvuHh/YVfHuPGZZzGgd3YjBWLMRsT"
    "RmMwenRGazSojcooURi5kSE1EiNGZIRGAN/wjPcXfDzGbVw4jcPYsRmrsWA2JmPEYPRGh9ZojBqVURoFciMzUiRGbEQIjcDw"
    "4X3HG3w8xm1cOI0Du7EZq7EYMyaMxmD0Rme0aFAblVEahZE7MiM1EiM2IoQIDN/wjPfnf3lw4zJO4zB2Y8OKxZiNyRiNwdEb"
    "ndEajVGjQmkURm5kRupIjNiIjNAI4MMz3p/35TFu48KJw9iNzViNxTEbkzEag9GjQ2s0Rm1URukojNzIjNRIECMyQiMwfMNz"
    "vD/3y2PcxmWcjsPYjc1YjQUzJmM0BqM3OkdrNEZtVEaJArmRGamRGLEjMkIjMHzDc7w/58tj3MZlnDiwG5uxGosxOyZjNAaj"
    "NzpHazRGbVRGiQK5kRmpkRixIzJCIzB8w3O8P/vLY9zGZZyOw9iNzViNxTEbkzEag9GjQ2s0Rm1URmkURm5kRupIjNiIjNAI"
    "HL7hGe/P+vIYt+MyTuMwdmNzrMZizMZkjI7B6I3OaI3GURuVURqFkTsyIzUSIzYiR2gEhm94xvszf+gxbuMyTuNw7MZmrMZi"
    "zI7JGI3B6I3O0RqNURuVUToKIzcyIzUSR2xERmgEhu/wjNf/8hi3cTlOHMZubI7VWL5jNibHaAxGb3RG62iM2qiM0igcuZEZ"
    "qZEYsSMyQiMwfMNzvD/jy2PcxmWcjsPYv2MzVsdizMZkjMbg6I3OaI3GqB2VURqFkRuZIzWS74iNyBEageEbnvH+9B96jNu4"
    "jNM4HLuxfcdqLI7ZmIzRGIze0Rmt0Ri1UTlKo/iO3MgcqZEYsREZoSMw/O/wjPen/dBj3MZlnMbh2I3NWI3FmB2TMX7HYPSO"
    "zmiNxqiNylEaxXfkRuZIjcSIjcgIHYHhf4dnvD/1hx7jNi7jNA7HbmzfsRqLYzYmYzQGo3d0RvsdjVE7KqP8jsLIHZmRGgli"
    "R+QIHYHDd3iO96f80IMbl+N0HI7dsTlWx+KYHZNjdAyOHh1aR+OoHZWjdBSO3JE5UkfiiB0RQgQO3+E53p/8Q4/jdlyO03E4"
    "dsfmWB2LY3ZMjhEDekfnaB2No3ZUjtJROHJH5kgdiSN2RI7QEcCH53h/0g89jttxOU7H4dgdm2N1LI7ZMTlGx+DoHZ2jdTSO"
    "2lE5SkfhyB2ZI3UkjhgRQkfg8B2e4/V+6HHcjstxOg7H7tgcq2NxzI7JMToGR+/oHK2jcdSOylE6CkfuyBypI3HEjsgROgKH"
    "7/A+/j+yt+r8"
)


_INTEL_XEON_6_167 = (
    "eNpdwzcYxGBAENBIjUgJ1UOKkRpAMCroSY2ocPQoxSDF2CPNACqhZ8x4Y8aMN2bMmPHGjBlvzJgxIyv/e9/3ovOvfyL62zfOfLJl"
    "yZwJz78Kb5z5ZMuKd954/WV458KRHSvemTLi5y/CKyf2rPlgxpjHn4ffnPlky5I5b7z+LLxz4cSeNQtmjHn8afjNmU+2rHjnjRE/"
    "XXjliwMblsyZ8PqT8M6FE3s2fDBjwvP/h3cuHNmz5oMZE57/L7xx4cieNR/MmPD8v+GdCyf2bPhgzoTXH4d3rnxxYMuSd94Y8fij"
    "8Jszn+xYs2DGmOcfhncunDiwYcmcN0b8tOE3Zz7ZseaDGRNe/ye8c+WLA1tWLJgy5vkH4Z0LJw5sWfLOlDHP3w9vXDhxYMuSd6aM"
    "ef5eeOfCiQNbViyYMub5u+GdK198smPFghkTXr8T/vDNmSN7Nnww540Rj/8d3rhw4sCWFQtmTHg14Q/fnDmyZ8OSd6aMef6v8M6V"
    "Lz7ZseaDOW+MePzP8M6VLz7ZseaDOW+MePyP8MaVLz7ZseaDOW+Mef738M6VLz7ZsWHJO1PGPP9b+MM3Z47s2bJiwYwJIx7/Nbxx"
    "4cQnO9Z88M6UMc//Ev7wzZkjB7asWDDnjRHPOrxz5YsjezasWDDjjRGP/xzeufLFkT0bViyY8caIx2+Hd658cWTPlhUL5rwx4vlb"
    "4Z1vzhw5sGXNB+9MGfP6zfCHGxe++GTHhiULZrwx4vkb4Z1vzhw5sGXNB+9MmfD6T+GDG1e+OLJny4oP5kwZ8/r18MGNK18c2bNl"
    "xQdzpkx4VeGDG1e+OHJgy5oP3pkxYcTjP4Z3vjlz4sCODUsWzHhjzPPXwh9uXPjiyJ4tKz54Z8qEEY9fDe98c+bEJzs2rFgwZ8qE"
    "16+ED+5cOXPiwI4NKxbMmTLh9cvhgztXzpz4ZMeGFR/MmTJhxOM/hHe+ufDFJ3u2rPngnRlvjHn++/CHG1fOHDmwY8OKBXOmTBjx"
    "KMM731z44sieLWuWLJgzZczrl8IHd7658MUne7asWbJgzpQxr18MH9z55sIXRw5sWbNkwZwpE0Y8fyH84caFL44c2LFhxQfvzHhj"
    "zOvnwwd3vrlw4pM9W9YsWTBnyoQRz58Lf7hx5cyJT/ZsWbNkwZwpE0Y8fzb84caVMyc+2bNlzZIFc6ZMGPH8mfCHG1cufHHkwI4N"
    "Kz54Z8YbY16P8MGdby6cOfHJni1rliyYM2XCiNdPhw/ufHPhiyMHdmxYs2TBnCkTRjx/KvzhzjcXvjhyYMeWNUsWzJkyYczr34UP"
    "7nxz4YsTn+zZsmbJB+/MeGPM69+GT364ceXMF0cO7NiwZsmCOVPeGPP6N+GDOzeunDnxyYEdG1YsWTBnyoQxr58MH9y5ceXMiSMH"
    "dmxYs2TBnBlvjHn96/DJDzeuXPjiyIE9W9as+OCdGVMmjHgV4YM731w5c+LIgR0b1ixZ8M6MNyaMeP5E+ODONxfOnPjkwI4Na5Ys"
    "eGfGGxNGPH88fHDnmytnThw5sGfLmhUfvDNnyoQxrx8Ln/xw45sLX5z4ZM+ODWuWLHhnxpQJI14/Gj64c+PKhS+OfLJnx4YVSxa8"
    "M2PKhBGvHwkf/HDjyoUvTnxyYMeGNUs+eGfOlAljXj8cPvnhzjdXzpw4cmDPlg0rlix4Z8aUCSNe/yp88MONby6cOXHkwJ4tG1Ys"
    "WfDOjDcmjHjdwwc/3PjmwpkTRw7s2bJhxZIF78yY8saYEc9/GT64c+PKhS9OfHJgx5Y1Kz5YMGfGlAljXv8ifPLDnW+unPniyCcH"
    "dmxZs+KDBXNmTJkw5vVD4ZMf7ty4cuGLE58c2LNlw4olC96ZM+WNMa8fDH+4ceHEgS1rPpjzxojnPw/vXPniyJ4NS96ZMeH1z8IH"
    "Ny6c+GTHmiXvTBnz+qfhD99cOHFgx5oP3pky5pWHP3xz4cQnO9YseWfGhNc/CR/cuPLFJ3s2rFgw540Rzx8I73xz5sSBHWuWvDNl"
    "wuv7wwc3rnxxZM+WFR+8M2XC6x+HD25c+eLIni0rPnhnyoTX94UPblw5c+TAljVL3pkxYcTze8M731w48cmODSsWzJky5vU94YMb"
    "V84cObBjzZIFM94Y88zCH25c+eLIgS1rliyY8caY13eHP9y4cubIgR0bliyYM2XM67vCB3e+OXPikz1bVnzwzow3Rjy/M/zhxpUz"
    "Rw7s2LDigzlTJox4fkf4w40LXxw5sGPDig/mTJkw4vnt4Q83rpw5cWDHhhUfvDPjjTGvbwsf3Pnmwhef7NmyZsmCOVMmjHj+o/CH"
    "G1fOnPhkz5Y1SxbMmTJhxDMNf7hx5cyJT/ZsWbNkwZwpE0Y8/2H44M43F744cmDHhhUfvDPjjTEjnt8a/nDjypkTn+zZsmbFB+/M"
    "eGPM61vCBz/cuHLmxCd7tmxY8cE7M94YM+L5zeEPN66c+eLIgR0bVixZMGfKhDGvbwof3PnmypkTn+zZsWHFB+/MmTJhxPMfhA/u"
    "fHPhzIlP9uzYsOKDBXOmTBjz+sbwwZ0bV86cOHJgx5Y1Sxa8M+ONCSOet/CHO99cOHPikwM7NqxYsmDOjDfGjHj+/fCHO99cOHPi"
    "kwM7NqxZsuCdGW9MGPH6hvDBnRtXznxx5MCeLRtWfLBgzow3xox4fn34w51vrpw5ceTAni1rVnywYM6MN8aMeH5d+ODOjStnvjjy"
    "yZ4dG1YsWfDOjCkTxry+Nnzyw41vLpw5ceTAni0bVixZ8M6MNyaMeH1N+OCHG99cOHPiyIE9WzasWLLgnRlTJox5fXX45MGdG1cu"
    "fHHikwM7tqxZ8cGCOTOmTBjzSsInP9z55sqZL058cmDHljUrlix4Z8aUCWNGPL8qfHDnxpULZ04cObBnx4Y1Sz5YMGfGGxPGvL4y"
    "fPLDnRtXLnxx4siBPTs2rFnywYI5M6ZMGPP6ivDJgzs3vrlw5osjn+zZsWXNiiUL3pkz5Y0JI15fHj754c6NKxfOnDjyyZ4dW9as"
    "WLLgnTkz3pgw5vX3wicP7tz45sKZL058cmDPlg1rVnyw4J0ZU96YMOL1ZeGTH+7c+ObCmS+OfHJgz5YNa1Z8sOCdOVPemDDm9XfD"
    "Jw9+uPHNlQtfnDjyyZ4dWzasWPLBgjkzprwxYcQrDp88uHPjmysXvjhx5JM9O7ZsWLPkgwXvzJnyxoQxI55fGj744c6NKxfOfHHi"
    "kwN7dmzZsGLJBwvemTHljQljRjy/JHzww50b31w488WJI5/s2bFlw5oVHyx4Z86MKW+MGfH64vDJgx/ufHPlwpkvThw5sGfHlg1r"
    "Vnyw4J05M6a8MWHE64vCJw9+uHPjmytnvjhx5JMDe3ZsWbNiyQcL3pkzY8qEMSNeXxg+efDDnRvfXDnzxYkjnxzYs2PLhjUrPljw"
    "zpwZU96YMGbE6wvCJw/u3PjmyoUzX5w48smBPTu2bFiz5IMF78yZMeWNCWNGvP5O+OTBD3dufHPlwpkTRz45sGfHlg1rViz5YME7"
    "c2ZMeWPCmBGvKHzy4Ic7N765cuHMFyeOfHJgz44tG9asWPLBgnfmzJjyxoRx+G8A2hD1MA=="
)

TABLES = {"amd-zen": _AMD_ZEN, "intel-xeon-6-167": _INTEL_XEON_6_167}


@lru_cache(maxsize=None)
def rsqrt_table(name: str = "amd-zen") -> np.ndarray:
    """The measured ``rsqrtps`` table ``name`` (a key of :data:`TABLES`) as a read-only float32
    array of 8192 entries."""
    t = np.frombuffer(zlib.decompress(base64.b64decode("".join(TABLES[name]))), dtype="<f4").astype(np.float32)
    t.setflags(write=False)
    return t
