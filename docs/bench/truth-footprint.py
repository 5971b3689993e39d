# PSNR of a full-size AO image box-averaged by f against a truth, sky from a linear-depth PFM
import sys, numpy as np
def pfm(p):
    with open(p,'rb') as f:
        kind=f.readline().strip(); w,h=map(int,f.readline().split()); s=float(f.readline())
        c=3 if kind==b'PF' else 1
        a=np.frombuffer(f.read(),dtype='<f4' if s<0 else '>f4').reshape(h,w,c)[::-1]
    return a[...,0] if c==1 else a
full=pfm(sys.argv[1]); truth=pfm(sys.argv[2]); f=int(sys.argv[3])
h,w=truth.shape
b=full[:h*f,:w*f].reshape(h,f,w,f).mean(axis=(1,3))
if len(sys.argv)>4:
    d=pfm(sys.argv[4]); d=d if d.ndim==2 else d[...,0]
    sky=(~np.isfinite(d))|(d>=999)
    sky=sky[:h*f,:w*f].reshape(h,f,w,f).mean(axis=(1,3))>=0.5
else:
    sky=np.zeros_like(truth,bool)
e=(b-truth)[~sky]
mse=(e.astype(np.float64)**2).mean()
print("pixels %d  rmse %.4f  psnr %.2f dB"%(e.size, mse**0.5, 10*np.log10(1/mse)))
